"""Bad inputs raise the documented exceptions, located: a bad scenario
(file, line, column, key, the CLI's message), NaN in a setter, wrong array
shapes, a non-unit quaternion; a refused setter changes nothing."""

import math

import numpy as np
import pytest

import clump
from conftest import run_cli


def test_bad_scenario_file(dimers):
    sc = dimers()
    text = sc.read_text().replace("dt = 5e-6", "dt = -5e-6")
    sc.write_text(text)
    with pytest.raises(clump.ScenarioError) as e:
        clump.Simulation.from_file(sc)
    err = e.value
    assert isinstance(err, ValueError)
    line = 1 + text[: text.index("dt = -5e-6")].count("\n")
    assert err.file == str(sc)
    assert err.line == line and err.column >= 1
    assert err.key == "simulation.dt"
    # the message is the CLI's, located as file:line
    assert f"{sc}:{line}" in str(err)


def test_unknown_key_and_toml_syntax(tmp_path, dimers):
    sc = dimers()
    text = sc.read_text().replace("friction = 0.4", "fricton = 0.4")
    with pytest.raises(clump.ScenarioError) as e:
        clump.Simulation.from_toml(text, base_dir=sc.parent, name="bad.toml")
    assert e.value.key == "contact.fricton" and e.value.line is not None
    assert "friction" in str(e.value)  # did you mean
    with pytest.raises(clump.ScenarioError) as e:
        clump.Simulation.from_toml("[simulation\ndt = 1", base_dir=tmp_path)
    assert e.value.line == 1


def test_bad_dict(dimers):
    import tomllib
    sc = dimers()
    d = tomllib.loads(sc.read_text())
    d["simulation"]["gravity"] = [0.0, 0.0, "down"]
    with pytest.raises(clump.ScenarioError) as e:
        clump.Simulation.from_dict(d, base_dir=sc.parent)
    assert e.value.file.endswith("<dict>") and e.value.key == "simulation.gravity"
    d["simulation"]["gravity"] = [0.0, 0.0, object()]
    with pytest.raises(clump.ScenarioError):
        clump.Simulation.from_dict(d, base_dir=sc.parent)


def test_missing_file_and_checkpoint(tmp_path):
    with pytest.raises(clump.ScenarioError) as e:
        clump.Simulation.from_file(tmp_path / "nope.toml")
    assert "nope.toml" in str(e.value)
    (tmp_path / "x.ckpt").write_bytes(b"not a checkpoint")
    with pytest.raises(clump.ScenarioError):
        clump.Simulation.from_checkpoint(tmp_path / "x.ckpt")
    with pytest.raises(clump.ScenarioError):
        clump.Template.from_file(tmp_path / "nope.txt")
    with pytest.raises(clump.ScenarioError):
        clump.Template(spheres=[[0, 0, 0, 0.01]], density=-1.0)


def test_setters_validate(dimers):
    sim = clump.Simulation.from_file(dimers())
    sim.run(steps=10)
    before = sim.final_state_json()
    v = sim.bodies.velocity
    bad = v.copy()
    bad[1, 2] = math.nan
    with pytest.raises(ValueError, match="finite"):
        sim.bodies.velocity = bad
    with pytest.raises(ValueError, match="shape"):
        sim.bodies.velocity = v[:2]
    with pytest.raises(ValueError, match="shape"):
        sim.bodies.position = np.zeros((3, 4))
    with pytest.raises(ValueError):
        sim.bodies.omega = "fast"
    q = sim.bodies.quaternion
    q[0] = [1.0, 0.1, 0.0, 0.0]
    with pytest.raises(ValueError, match="norm"):
        sim.bodies.quaternion = q
    with pytest.raises(ValueError, match="finite"):
        sim.walls["floor"].velocity = [0.0, math.inf, 0.0]
    with pytest.raises(ValueError):
        sim.walls["floor"].velocity = [0.0, 1.0]
    with pytest.raises(KeyError):
        sim.walls["ceiling"]
    with pytest.raises(ValueError):
        sim.bodies.force_flag = np.full((3, 3), 2.0)
    with pytest.raises(ValueError):
        sim.run(steps=1, time=1.0)
    with pytest.raises(ValueError):
        sim.run(time=math.nan)
    with pytest.raises(ValueError):
        sim.run(steps=1, every=0)
    assert sim.final_state_json() == before  # nothing was changed
    # a unit quaternion within 1e-6 is accepted (normalised)
    q[0] = [1.0 + 1e-9, 0.0, 0.0, 0.0]
    sim.bodies.quaternion = q
    # a callback's exception stops the run and propagates, state intact
    def boom(s):
        raise RuntimeError("from the callback")
    with pytest.raises(RuntimeError, match="from the callback"):
        sim.run(steps=100, callback=boom, every=5)
    assert sim.step_count == 15


def test_unstable_run_raises(tmp_path):
    """Contacts too soft for a 200 m/s impact (Hertz overlap ≈ 0.58 R) with
    the overlap limit set to 0.2: the health check's message, as
    UnstableError, at a step boundary."""
    (tmp_path / "bodies.csv").write_text("template,x,y,z,vz\nball,0,0,0.05,-200\n")
    (tmp_path / "s.toml").write_text("""
[simulation]
dt = 1e-6
gravity = [0.0, 0.0, -9.81]
max_overlap_ratio = 0.2
[domain]
lo = [-0.1, -0.1, -0.1]
hi = [0.1, 0.1, 0.1]
[[material]]
name = "m"
youngs_modulus = 1e9
poisson_ratio = 0.3
density = 2500
[[material]]
name = "rigid"
youngs_modulus = inf
poisson_ratio = 0.3
density = 0
[[template]]
name = "ball"
material = "m"
spheres = [[0.0, 0.0, 0.0, 0.01]]
[[wall]]
name = "floor"
material = "rigid"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
[[insert]]
kind = "file"
file = "bodies.csv"
[[stage]]
steps = 2000
""")
    sim = clump.Simulation.from_file(tmp_path / "s.toml")
    with pytest.raises(clump.UnstableError, match="overlaps wall 0") as e:
        sim.run()
    assert isinstance(e.value, clump.SimulationError)
    assert "too soft for the impact speed" in str(e.value)
    assert 0 < sim.step_count < 2000
