"""``device="gpu"``: the GPU path (crate clump-gpu) takes the steps between
events, built with the package's ``gpu`` feature
(``MATURIN_PEP517_ARGS="--features gpu" pip install ./crates/clump-py``).

Built with it, a short run of the GPU suite's poured bed
(crates/clump-cli/tests/fixtures/gpu_pour.toml: rods in a box of five
planes, contacts from the first steps) ends within 1e-12 of the box of
the same run on the CPU path, the tolerance of ``clump run --device gpu``
(crates/clump-cli/tests/device_gpu.rs: the device sums each body's
contact loads in another order; measured about 1e-15), and the
manifest names the adapter. Built without it, ``device="gpu"`` is
refused with the build command. Either way an unknown device is refused."""

import json
import pathlib

import numpy as np
import pytest

import clump

POUR = pathlib.Path(__file__).resolve().parents[2] / "clump-cli/tests/fixtures/gpu_pour.toml"
BOX = 0.061  # the bed's largest box edge, m
STEPS = 300


def gpu_or_reason(**kw):
    """A GPU simulation of the poured bed, or the refusal's message."""
    try:
        return clump.Simulation.from_file(POUR, device="gpu", **kw), None
    except ValueError as e:
        return None, str(e)


def test_an_unknown_device_is_refused():
    with pytest.raises(ValueError, match='device must be "cpu" or "gpu"'):
        clump.Simulation.from_file(POUR, device="tpu")


def test_gpu_runs_agree_with_the_cpu_path_or_the_build_is_named(tmp_path):
    gpu, why = gpu_or_reason(output_dir=tmp_path / "gpu")
    if gpu is None:
        assert "built without the GPU path" in why, why
        assert '--features gpu' in why, why
        return
    cpu = clump.Simulation.from_file(POUR)
    gpu.run(steps=STEPS)
    cpu.run(steps=STEPS)
    assert gpu.step_count == cpu.step_count == STEPS
    diff = np.abs(gpu.bodies.position - cpu.bodies.position).max() / BOX
    print(f"device=gpu after {STEPS} steps: largest |x - x_cpu| / L = {diff:.3e}")
    assert diff < 1e-12
    gpu.run()  # to the end of the stages: the manifest is written
    manifest = json.loads((tmp_path / "gpu" / "manifest.json").read_text())
    assert manifest["device"] == "gpu"
    assert manifest["adapter"], manifest
