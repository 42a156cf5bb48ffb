"""The Python examples run as shipped, in their short form
(CLUMP_EXAMPLE_SHORT=1), and say what they claim."""

import os
import subprocess
import sys

from conftest import REPO

EXAMPLES = REPO / "examples" / "python"


def run_example(name, tmp_path, *args):
    env = dict(os.environ, CLUMP_EXAMPLE_SHORT="1", MPLBACKEND="Agg")
    p = subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)], cwd=tmp_path,
                       env=env, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


def test_restitution_sweep(tmp_path):
    out = run_example("restitution_sweep.py", tmp_path, tmp_path / "sweep")
    assert (tmp_path / "sweep" / "rebound.png").stat().st_size > 1000
    # the rebound heights follow e² within the documented few per cent
    for line in out.splitlines():
        if line.startswith("e = "):
            h1 = float(line.split("rebound to ")[1].split()[0])
            th = float(line.split("e² h0 = ")[1].split()[0])
            assert abs(h1 - th) / th < 0.05, line


def test_servo_piston(tmp_path):
    out = run_example("servo_piston.py", tmp_path, tmp_path / "servo")
    assert (tmp_path / "servo" / "servo.png").exists()
    import numpy as np
    t, p, z, v = np.loadtxt(tmp_path / "servo" / "servo.csv", delimiter=",", skiprows=1).T
    assert p.max() > 0 and z[-1] < z[0]  # the piston went down and met the bed
    assert "controller calls" in out


def test_read_outputs(tmp_path):
    out = run_example("read_outputs.py", tmp_path)
    run = tmp_path / "out" / "python_t_handle"
    assert (run / "summary.png").exists() and "completed" in out
