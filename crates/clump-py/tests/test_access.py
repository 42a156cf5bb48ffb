"""Accessors agree with each other and with mechanics: contact forces sum
to the bodies' forces, ω = R ω_body, L = R I Rᵀ ω, spheres sit on their
bodies, walls feel the weight, DOF flags freeze motion."""

import numpy as np

import clump


def rot(q):
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def test_state_is_consistent(dimers):
    sim = clump.Simulation.from_file(dimers())
    assert len(sim.bodies) == 3 and sim.template_names == ["dimer"]
    assert list(sim.bodies.template_name) == ["dimer"] * 3
    sim.run(steps=6999)  # the dimers landed at about step 5000
    b = sim.bodies
    # contact forces (on sphere i; the partner gets the negative) + weight = body force
    c = sim.contacts()
    f = np.zeros((3, 3))
    row = {int(i): k for k, i in enumerate(b.id)}
    for k in range(len(c["overlap"])):
        fk = c["force_normal"][k] + c["force_tangential"][k]
        f[row[int(c["body_i"][k])]] += fk
        if c["body_j"][k] >= 0:
            f[row[int(c["body_j"][k])]] -= fk
    f += b.mass[:, None] * sim.gravity
    assert np.allclose(f, b.force, rtol=1e-9, atol=1e-12 * np.abs(b.force).max())
    # the floor feels the negative of its contacts' forces on the spheres
    on_wall = c["wall"] == 0
    assert on_wall.any() and (c["sphere_j"][on_wall] == -1).all()
    f_wall = -(c["force_normal"][on_wall] + c["force_tangential"][on_wall]).sum(axis=0)
    assert f_wall[2] < 0
    assert np.allclose(sim.walls["floor"].force, f_wall, rtol=1e-9, atol=1e-12 * abs(f_wall[2]))
    assert list(sim.walls) == ["floor"] and "floor" in sim.walls
    for q, w, wb, L, I in zip(b.quaternion, b.omega, b.omega_body, b.angular_momentum, b.inertia):
        R = rot(q)
        assert np.allclose(R @ wb, w, atol=1e-12)
        assert np.allclose(R @ (I * (R.T @ w)), L, rtol=1e-9, atol=1e-16)
    # spheres: two per body, at the template offsets (±2 mm along body x)
    s = sim.spheres
    assert len(s) == 6 and np.allclose(s.radius, 0.003)
    for k, bid in enumerate(b.id):
        mine = s.position[s.body == bid]
        assert len(mine) == 2
        assert np.allclose(mine.mean(axis=0), b.position[k], atol=1e-12)
        assert np.isclose(np.linalg.norm(mine[0] - mine[1]), 0.004, rtol=1e-9)
    assert sim.thermo()["bodies"] == 3


def test_flags_and_walls_steer(dimers):
    sim = clump.Simulation.from_file(dimers())
    sim.run(steps=10)
    ff = sim.bodies.force_flag
    assert ff.dtype == bool and ff.all()
    ff[:, 2] = False  # freeze vertical motion of all bodies
    sim.bodies.force_flag = ff
    vz = sim.bodies.velocity[:, 2].copy()
    sim.run(steps=100)
    assert np.array_equal(sim.bodies.velocity[:, 2], vz)
    floor = sim.walls["floor"]
    floor.velocity = [0.0, 0.0, 0.01]
    sim.run(steps=100)
    assert np.allclose(floor.center, [0.0, 0.0, 100 * sim.dt * 0.01], rtol=1e-9)
    sim.gravity = [0.0, 0.0, 0.0]
    assert sim.gravity[2] == 0.0


def test_setting_what_was_read_changes_no_bit(dimers):
    """position, velocity and flags written back as read leave the run's
    bits unchanged (no renormalisation, no recomputed momentum)."""
    a = clump.Simulation.from_file(dimers("a"))
    b = clump.Simulation.from_file(dimers("b"))
    a.run(steps=5500)

    def rewrite(s):
        s.bodies.position = s.bodies.position
        s.bodies.velocity = s.bodies.velocity
        s.bodies.force_flag = s.bodies.force_flag

    b.run(steps=5500, callback=rewrite, every=250)
    assert a.final_state_json() == b.final_state_json()


def heated(dimers, name):
    """The dimer scenario with heat: the grain conducts, the floor is
    adiabatic (its material has no heat keys)."""
    p = dimers(name)
    text = p.read_text().replace(
        'density = 2500\n',
        'density = 2500\nthermal_conductivity = 2.0\nspecific_heat = 800.0\n', 1)
    text = text.replace('spheres = [[-0.002, 0.0, 0.0, 0.003], [0.002, 0.0, 0.0, 0.003]]\n',
                        'spheres = [[-0.002, 0.0, 0.0, 0.003], [0.002, 0.0, 0.0, 0.003]]\n'
                        'temperature = 300.0\n')
    p.write_text(text + "\n[heat]\n")
    return p


def test_temperatures_read_set_and_conserve_heat(dimers):
    sim = clump.Simulation.from_file(heated(dimers, "hot"))
    t = sim.bodies.temperature
    assert t.shape == (3,) and (t == 300.0).all()
    sim.bodies.temperature = [400.0, 300.0, 350.0]
    assert list(sim.bodies.temperature) == [400.0, 300.0, 350.0]
    c = sim.bodies.mass * 800.0
    content = (c * sim.bodies.temperature).sum()
    assert np.isclose(sim.thermo()["heat_content[J]"], content, rtol=1e-14)
    sim.run(steps=6999)  # the dimers land and touch the floor and each other
    t = sim.bodies.temperature
    # the floor is adiabatic: the bodies' heat stays, and it flowed
    assert np.isclose((c * t).sum(), content, rtol=1e-12)
    assert sim.thermo()["max_temperature[K]"] == t.max()
    # bad values change nothing
    for bad in ([0.0, 300.0, 300.0], [300.0, 300.0], [float("nan")] * 3):
        try:
            sim.bodies.temperature = bad
        except ValueError:
            pass
        else:
            raise AssertionError(f"accepted {bad}")
    assert np.array_equal(sim.bodies.temperature, t)
    sim.bodies.heat_source = [0.0, 0.0, 1e-3]
    assert list(sim.bodies.heat_source) == [0.0, 0.0, 1e-3]


def test_temperature_without_heat_is_an_error(dimers):
    sim = clump.Simulation.from_file(dimers())
    try:
        sim.bodies.temperature
    except ValueError as e:
        assert "[heat]" in str(e)
    else:
        raise AssertionError("a temperature without [heat]")
