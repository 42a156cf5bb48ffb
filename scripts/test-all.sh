#!/usr/bin/env bash
# Every test suite of the repository, the README's one test command:
#   1. the Rust suite: cargo test --workspace --profile ci (needs no Python;
#      it compiles and runs the C API's example examples/c with the system cc),
#      and clump-core's API docs built without a warning;
#   2. the Python package: a virtual environment (.venv-test, or $CLUMP_VENV)
#      with maturin, numpy, pytest and matplotlib, `pip install
#      ./crates/clump-py` (the same `ci` build, with the `gpu` feature:
#      device="gpu", tested on the machine's Vulkan adapter) and its pytest
#      suite, which also runs the examples in examples/python in their short
#      form and compares against the `clump` binary built by step 1;
#   3. the MPI suite: `clump` built with the `mpi` feature (OpenMPI), run by
#      `mpirun -np 2, 3, 4` against one process (crates/clump-cli/tests/mpi.rs);
#   4. the GPU suite: `clump` built with the `gpu` feature, `clump check|bench
#      --device gpu` on the machine's Vulkan adapter (Mesa's lavapipe in CI,
#      crates/clump-cli/tests/device_gpu.rs). The device step's own tests
#      (crates/clump-gpu: f64 kernels, the step against the CPU path,
#      run-to-run bits) run in step 1.
# Every suite always runs; the exit status is non-zero if either failed.
# All three build with the `ci` profile (root Cargo.toml): the release
# profile's optimisation, without link-time optimisation, which cut the Rust
# suite's build on a 2-core machine from 29.5 to 5.2 min. The bits a run
# gives do not depend on it (docs/testing.md).
set -euo pipefail
cd "$(dirname "$0")/.."

status=0
echo "== Rust suite: cargo test --workspace --profile ci --no-fail-fast"
cargo test --workspace --profile ci --no-fail-fast || status=1

echo "== API docs: cargo doc -p clump-core --no-deps, warnings are errors"
RUSTDOCFLAGS="-D warnings" cargo doc -p clump-core --no-deps --profile ci || status=1

echo "== Python package: crates/clump-py"
venv="${CLUMP_VENV:-.venv-test}"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
# shellcheck disable=SC1091
source "$venv/bin/activate"
python -m pip install -q --upgrade pip
# maturin in the range crates/clump-py/pyproject.toml asks for: the package
# is built without build isolation, so pip would not enforce it
python -m pip install -q "maturin>=1.5,<2" numpy pytest matplotlib
# maturin from the venv builds the extension with the `ci` profile, as
# `clump` above (a failed build fails the suite, and the MPI suite still runs);
# with the `gpu` feature, so that test_gpu.py runs device="gpu" on lavapipe
# (about doubles the package's build: wgpu, and clump-core with `testbed`)
if MATURIN_PEP517_ARGS="--profile ci --features gpu" python -m pip install -q --no-build-isolation --force-reinstall --no-deps ./crates/clump-py; then
  export CLUMP_BIN="$PWD/target/ci/clump"
  if [ ! -x "$CLUMP_BIN" ]; then
    cargo build --profile ci -p clump-cli
  fi
  python -m pytest -q crates/clump-py/tests || status=1
else
  echo "== FAILED: the Python package did not build"
  status=1
fi
deactivate

echo "== MPI suite: cargo test --profile ci -p clump-cli --features mpi --test mpi -- --test-threads=1"
if command -v mpirun >/dev/null 2>&1; then
  # one test at a time: parallel mpirun jobs oversubscribe the cores, and
  # mpirun gives SIGTERMed ranks only 1 s (odls_base_sigkill_timeout) to
  # write their checkpoint
  cargo test --profile ci -p clump-cli --features mpi --test mpi -- --test-threads=1 || status=1
else
  echo "error: mpirun not found (Debian: openmpi-bin libopenmpi-dev); the MPI suite cannot run"
  status=1
fi

echo "== GPU suite: cargo test --profile ci -p clump-cli --features gpu --test device_gpu"
cargo test --profile ci -p clump-cli --features gpu --test device_gpu || status=1

if [ "$status" -ne 0 ]; then
  echo "== FAILED: at least one suite failed (see above)"
fi
exit "$status"
