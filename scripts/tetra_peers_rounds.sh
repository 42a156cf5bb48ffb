#!/usr/bin/env bash
# The shared tetra bed (2 000 clumps) with Clump beside both peers, back to
# back, round by round: per round `clump bench` on 1 thread and on 2 threads
# (each beside one LIGGGHTS run, serial), then LAMMPS (`fix rigid/small`,
# `pair granular`, ../shared/bench/tetra-bed/lammps/in.bench) on 1 and on
# 2 ranks. Prints each run's phase-B line; LAMMPS' phase B is its second
# `Loop time`. Run from the repository root after
# `cargo build --release -p clump-cli`; needs lmp, mpirun, liggghts and
# python3 with numpy and scipy (Debian: lammps, liggghts, python3-scipy;
# PYTHON names another interpreter).
#
#   scripts/tetra_peers_rounds.sh [ROUNDS=3] [WORK=out/tetra-peers]
set -euo pipefail
rounds=${1:-3}
work=$(realpath -m "${2:-out/tetra-peers}")
shared=$(realpath ../shared/bench/tetra-bed)
clump=$(realpath target/release/clump)
py=${PYTHON:-python3}
if ! "$py" -c 'import numpy, scipy' 2>/dev/null; then
    echo "$py has no numpy or scipy: install them (Debian: python3-numpy python3-scipy) or name another interpreter with PYTHON=..." >&2
    exit 2
fi
# `clump bench` runs the shared generator with the `python3` found first on
# PATH: make that the interpreter just checked
pydir=$(dirname "$(command -v "$py")")
export PATH="$pydir:$PATH"
mkdir -p "$work"
cp "$shared/make_ic.py" "$shared/tetra.xyzr" "$shared/lammps/in.bench" "$shared/lammps/gen_lammps.py" "$work/"
(
    cd "$work"
    "$py" make_ic.py 2000 >/dev/null
    cmp ic_2000.txt "$shared/ic_2000.txt" # the shared initial condition
    "$py" gen_lammps.py 2000 0.2 >/dev/null
)
mpi=(mpirun --allow-run-as-root --oversubscribe)
for r in $(seq 1 "$rounds"); do
    for t in 1 2; do
        "$clump" bench --n 2000 --threads "$t" --liggghts-rounds 1 2>&1 |
            grep -E "^round 0|phase B ratio" | sed "s/^/round $r, clump $t thread(s): /"
    done
    for p in 1 2; do
        (cd "$work" && "${mpi[@]}" -np "$p" lmp -in in.bench -var N 2000 -var ZTOP 0.2 \
            -var NA 40000 -var NB 10000 -var PX "$p" -log "log_r${r}_np${p}.lammps" >/dev/null)
        b=$(grep "^Loop time" "$work/log_r${r}_np${p}.lammps" | sed -n 2p)
        echo "round $r, lammps $p rank(s): $b"
    done
done
