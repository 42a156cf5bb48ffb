"""The same bits as the CLI: a scenario run from Python ends in the state
`clump run` ends in, bit for bit (final_state.json holds the f64 bit
patterns), also with callbacks that read the state, from a checkpoint of
either, and when a callback sets a velocity where a stage would."""

import struct

import numpy as np

import clump
from conftest import final_state, run_cli


def cli_final(scenario, out):
    run_cli("run", scenario, "-o", out)
    return final_state(out / "final_state.json")


def bits(a):
    return [format(struct.unpack("<Q", struct.pack("<d", float(x)))[0], "016x") for x in a]


def test_run_equals_clump_run(dimers, tmp_path):
    sc = dimers()
    expected = cli_final(sc, tmp_path / "cli")
    sim = clump.Simulation.from_file(sc)
    sim.run()
    assert sim.finished and sim.step_count == 7000
    assert final_state(sim.final_state_json()) == expected
    # the accessors give those very bits (bodies sorted by id)
    pos, vel, q = sim.bodies.position, sim.bodies.velocity, sim.bodies.quaternion
    for k, b in enumerate(expected["bodies"]):
        assert sim.bodies.id[k] == b["id"]
        assert bits(pos[k]) == b["position_bits"]
        assert bits(vel[k]) == b["velocity_bits"]
        assert bits(q[k]) == b["orientation_bits"]


def test_callbacks_that_read_change_nothing(dimers, tmp_path):
    sc = dimers()
    expected = cli_final(sc, tmp_path / "cli")
    sim = clump.Simulation.from_file(sc)
    calls = []

    def look(s):
        calls.append(s.step_count)
        s.bodies.position, s.contacts(), s.thermo(), s.walls["floor"].force

    sim.run(steps=2500, callback=look, every=7)
    sim.run(callback=look, every=1000)
    sim.run()  # nothing left
    assert calls[:2] == [7, 14] and calls[-1] == 6500  # 7000 ends the stages
    assert final_state(sim.final_state_json()) == expected


def test_checkpoint_continuation(dimers, tmp_path):
    sc = dimers()
    cli_dir = tmp_path / "cli"
    expected = cli_final(sc, cli_dir)
    # a CLI checkpoint at step 2500, continued in Python
    part = tmp_path / "part"
    run_cli("run", sc, "-o", part, "--steps", 2500)
    ckpt = part / "checkpoint_000002500.ckpt"
    sim = clump.Simulation.from_checkpoint(ckpt)
    assert sim.step_count == 2500
    sim.run()
    assert final_state(sim.final_state_json()) == expected
    # a Python checkpoint, continued in Python and by `clump resume`
    sim = clump.Simulation.from_file(sc)
    sim.run(steps=4321)
    mine = tmp_path / "py" / "state.ckpt"
    mine.parent.mkdir()
    sim.save_checkpoint(mine)
    sim.run()
    assert final_state(sim.final_state_json()) == expected
    again = clump.Simulation.from_checkpoint(mine)
    assert again.step_count == 4321
    again.run()
    assert final_state(again.final_state_json()) == expected
    # a checkpoint outside a run folder resumes into the folder the user
    # names (`clump resume` never writes into a loose folder)
    out = tmp_path / "resumed"
    run_cli("resume", mine, "-o", out)
    assert final_state(out / "final_state.json") == expected


def test_velocity_setter_equals_stage_body(dimers, tmp_path):
    kick = "[[stage.body]]\nid = 2\nvelocity = [0.3, -0.1, 0.2]\nangular_velocity = [0.0, 40.0, 5.0]"
    staged = dimers("staged", kick)
    expected = cli_final(staged, tmp_path / "cli")
    plain = dimers("plain")
    sim = clump.Simulation.from_file(plain)

    def steer(s):
        if s.step_count == 3000:
            assert s.stage == "kicked"
            v, w = s.bodies.velocity, s.bodies.omega
            k = int(np.flatnonzero(s.bodies.id == 2)[0])
            v[k] = [0.3, -0.1, 0.2]
            w[k] = [0.0, 40.0, 5.0]
            s.bodies.velocity = v
            s.bodies.omega = w

    sim.run(callback=steer, every=1000)
    assert final_state(sim.final_state_json()) == expected
    # and without the kick, the run differs
    assert final_state(clump.Simulation.from_file(plain).final_state_json()) != expected


def test_from_dict_and_toml_equal_file(dimers, tmp_path):
    import tomllib
    sc = dimers()
    text = sc.read_text()
    a = clump.Simulation.from_file(sc)
    b = clump.Simulation.from_toml(text, base_dir=sc.parent)
    c = clump.Simulation.from_dict(tomllib.loads(text), base_dir=sc.parent)
    for s in (a, b, c):
        s.run(steps=1500)
    assert a.final_state_json() == b.final_state_json() == c.final_state_json()


def test_outputs_like_cli(dimers, tmp_path):
    """With output_dir the run writes clump run's files; thermo() gives
    thermo.csv's row (same column names, same values)."""
    import csv
    sc = dimers()
    out = tmp_path / "pyout"
    sim = clump.Simulation.from_file(sc, output_dir=out)
    sim.run(steps=3000)
    row = sim.thermo()
    sim.run()
    rows = list(csv.DictReader(open(out / "thermo.csv")))
    at = next(r for r in rows if r["step"] == "3000")
    assert list(row) == list(at)
    for k, v in row.items():
        assert float(at[k]) == v, k  # thermo.csv prints shortest round-trip floats
    cli = cli_final(sc, tmp_path / "cli")
    assert final_state(out / "final_state.json") == cli
    sim.write_vtk(tmp_path / "vtk")
    assert (tmp_path / "vtk" / "spheres.pvd").exists()
