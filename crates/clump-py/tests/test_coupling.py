"""sim.coupling: external loads against Newton's second law for a velocity
Verlet step, the fluid force at a per-body fluid velocity against Stokes'
law, at a per-body void fraction against Di Felice's (1994) law written
out here, the void fraction on a grid against the sphere's volume, fields
on grids (a linear velocity field interpolated exactly, a void fraction per
cell) read at each body, and bad arrays refused with a message."""

import math

import numpy as np
import pytest

import clump

R = 0.001  # ball radius, m
RHO = 2500.0  # kg/m^3
DT = 1e-5  # s
MU, RHO_F = 1e-3, 1000.0  # water


def balls(tmp_path, rows: str, fluid: str = "") -> clump.Simulation:
    """Balls of radius R from CSV rows (after the header), no gravity."""
    (tmp_path / "bodies.csv").write_text(
        "template,x,y,z,vx,vy,vz,ffx,ffy,ffz,driven\n" + rows)
    text = f"""
[simulation]
dt = {DT}
gravity = [0.0, 0.0, 0.0]

[domain]
lo = [-0.02, -0.02, 0.0]
hi = [0.02, 0.02, 0.02]

[[material]]
name = "glass"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = {RHO}

[contact]
restitution = 0.5
friction = 0.4

[[template]]
name = "ball"
material = "glass"
spheres = [[0.0, 0.0, 0.0, {R}]]

[[insert]]
kind = "file"
file = "bodies.csv"

[[stage]]
name = "run"
steps = 1000
{fluid}
"""
    return clump.Simulation.from_toml(text, base_dir=tmp_path)


# two free balls moving at 5 cm/s (a run at rest would trip the kinetic
# energy jump check on the first push), and two held in place
FREE = "ball,0.01,0,0.01,0,0.05,0,1,1,1,0\nball,-0.01,0,0.01,0,0.05,0,1,1,1,0\n"
FIXED = "ball,0.01,0,0.01,0,0,0,1,1,1,1\nball,-0.01,0,0.01,0,0,0,1,1,1,1\n"


def test_external_loads_follow_newtons_second_law(tmp_path):
    sim = balls(tmp_path, FREE)
    m = sim.bodies.mass
    assert m[0] == pytest.approx(4 / 3 * math.pi * R**3 * RHO, rel=1e-12)
    f, tz = 2e-5, 3e-11
    sim.coupling.set_external_loads([[f, 0, 0], [0, 0, 0]], [[0, 0, 0], [0, 0, tz]])
    sim.coupling.set_external_loads([[0, 0, 0], [0, 0, f]], persistent=False)
    n = 40
    sim.run(steps=n)
    v, w = sim.bodies.velocity, sim.bodies.omega
    # a load set at a boundary enters the force evaluation at the end of
    # the next step: N steps give F (N - 1/2) dt, a one-step load F dt
    assert v[0, 0] == pytest.approx(f * (n - 0.5) * DT / m[0], rel=1e-12)
    assert v[1, 2] == pytest.approx(f * DT / m[1], rel=1e-12)
    assert w[1, 2] == pytest.approx(tz * (n - 0.5) * DT / (0.4 * m[1] * R * R), rel=1e-12)
    sim.coupling.clear()
    sim.run(steps=3)
    # the last half kick of the load, then nothing
    assert sim.bodies.velocity[0, 0] == pytest.approx(f * n * DT / m[0], rel=1e-12)


def test_fluid_force_at_a_per_body_fluid_velocity_is_stokes_drag(tmp_path):
    fluid = f'[fluid]\ndensity = {RHO_F}\nviscosity = {MU}\ndrag = "stokes"\nbuoyancy = false\n'
    sim = balls(tmp_path, FIXED, fluid)
    u = np.array([[0.0, 0.0, 1e-3], [2e-3, -1e-3, 0.0]])
    sim.coupling.set_fluid_velocity(u)
    sim.step()
    assert np.all(sim.bodies.velocity == 0.0)
    expect = 3 * math.pi * MU * 2 * R * u  # Stokes (1851) on a body at rest
    np.testing.assert_allclose(sim.coupling.fluid_force, expect, rtol=1e-12, atol=0)


def di_felice(eps: float, w: float, d: float) -> float:
    """Di Felice (1994) drag magnitude on a sphere at interstitial slip w:
    Re = rho eps w d/mu, Cd = (0.63 + 4.8/sqrt(Re))^2 (Dallavalle),
    F = pi/8 rho d^2 Cd (eps w)^2 eps^-chi,
    chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2/2)."""
    re = RHO_F * eps * w * d / MU
    cd = (0.63 + 4.8 / math.sqrt(re)) ** 2
    chi = 3.7 - 0.65 * math.exp(-((1.5 - math.log10(re)) ** 2) / 2)
    return math.pi / 8 * RHO_F * d * d * cd * (eps * w) ** 2 * eps ** (-chi)


def test_void_fraction_at_each_body_enters_di_felice_drag(tmp_path):
    fluid = (f'[fluid]\ndensity = {RHO_F}\nviscosity = {MU}\ndrag = "di_felice"\n'
             'buoyancy = false\nvelocity = [0.0, 0.0, 0.02]\n')
    sim = balls(tmp_path, FIXED, fluid)
    eps = np.array([0.45, 0.8])
    sim.coupling.set_void_fractions(eps)
    sim.step()
    fz = sim.coupling.fluid_force[:, 2]
    for k in range(2):
        assert fz[k] == pytest.approx(di_felice(eps[k], 0.02, 2 * R), rel=1e-12)
    # the uniform velocity set from Python replaces [fluid] velocity
    sim.coupling.set_fluid_velocity([0.0, 0.0, 0.01])
    sim.step()
    assert sim.coupling.fluid_force[0, 2] == pytest.approx(di_felice(0.45, 0.01, 2 * R), rel=1e-12)


def test_void_fraction_on_a_grid(tmp_path):
    sim = balls(tmp_path, FIXED)
    v = 4 / 3 * math.pi * R**3
    # one 4 mm cell around the ball at x = 0.01: 1 - V/V_cell
    e = sim.coupling.void_fraction([0.008, -0.002, 0.008], [0.004] * 3, (1, 1, 1))
    assert e.shape == (1, 1, 1)
    assert e[0, 0, 0] == pytest.approx(1 - v / 0.004**3, rel=1e-12)
    # 2x2x2 cells of 2 mm whose common corner is the ball's centre: V/8 in each
    e = sim.coupling.void_fraction([0.008, -0.002, 0.008], [0.002] * 3, (2, 2, 2))
    np.testing.assert_allclose(e, 1 - v / 8 / 0.002**3, rtol=1e-12)
    # layers along z: indexed [i, j, k]
    # (both balls, at z = 10 mm, lie wholly in the third 4 mm layer)
    e = sim.coupling.void_fraction([-0.02, -0.02, 0.0], [0.04, 0.04, 0.004], (1, 1, 4))
    assert e.shape == (1, 1, 4)
    np.testing.assert_array_equal(e[0, 0, [0, 1, 3]], 1.0)
    assert e[0, 0, 2] == pytest.approx(1 - 2 * v / (0.04 * 0.04 * 0.004), rel=1e-12)


def test_bad_arrays_are_refused_and_change_nothing(tmp_path):
    sim = balls(tmp_path, FREE)
    with pytest.raises(ValueError, match=r"force must have shape \(2, 3\), got \[3, 3\]"):
        sim.coupling.set_external_loads(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="non-finite"):
        sim.coupling.set_external_loads([[0, 0, np.nan], [0, 0, 0]])
    with pytest.raises(ValueError, match=r"\(0, 1\]"):
        sim.coupling.set_void_fractions([0.5, 1.5])
    with pytest.raises(ValueError, match="no fluid"):
        sim.coupling.set_fluid_velocity([0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="positive edges"):
        sim.coupling.void_fraction([0, 0, 0], [0.0, 1.0, 1.0], (1, 1, 1))
    sim.run(steps=5)
    np.testing.assert_array_equal(sim.bodies.velocity[:, 0], 0.0)
    np.testing.assert_array_equal(sim.coupling.fluid_force, 0.0)


def test_fluid_velocity_grid_is_interpolated_at_each_body(tmp_path):
    # a field linear in x, y, z on a regular grid: trilinear interpolation
    # gives it exactly at each held ball, and Stokes' drag 3 pi mu d u
    fluid = f'[fluid]\ndensity = {RHO_F}\nviscosity = {MU}\ndrag = "stokes"\nbuoyancy = false\n'
    sim = balls(tmp_path, FIXED, fluid)

    def u(p):
        x, y, z = p
        return np.array([1e-3 + 0.1 * x, -0.05 * z, 0.2 * y + 0.03 * x + 1e-3])

    origin, spacing, n = np.array([-0.02, -0.02, 0.0]), np.array([0.015, 0.02, 0.007]), (4, 3, 4)
    grid = np.zeros(n + (3,))
    for i, j, k in np.ndindex(*n):
        grid[i, j, k] = u(origin + np.array([i, j, k]) * spacing)
    sim.coupling.set_fluid_velocity_grid(origin, spacing, grid)
    sim.step()
    x = sim.bodies.position
    expect = np.array([3 * math.pi * MU * 2 * R * u(p) for p in x])
    np.testing.assert_allclose(sim.coupling.fluid_force, expect, rtol=1e-12, atol=1e-22)
    # removed: the uniform velocity (0) again
    sim.coupling.set_fluid_velocity_grid(None, None, None)
    sim.step()
    np.testing.assert_array_equal(sim.coupling.fluid_force, 0.0)


def test_void_fraction_field_is_read_at_each_body(tmp_path):
    fluid = (f'[fluid]\ndensity = {RHO_F}\nviscosity = {MU}\ndrag = "di_felice"\n'
             'buoyancy = false\nvelocity = [0.0, 0.0, 0.02]\n')
    sim = balls(tmp_path, FIXED, fluid)
    # two cells along x: the ball at x = -10 mm in the first, x = 10 mm in the second
    eps = np.array([0.45, 0.8]).reshape(2, 1, 1)
    sim.coupling.set_void_fraction_field([-0.02, -0.02, 0.0], [0.02, 0.04, 0.02], eps)
    sim.step()
    fz = sim.coupling.fluid_force[:, 2]
    assert fz[0] == pytest.approx(di_felice(0.8, 0.02, 2 * R), rel=1e-12)
    assert fz[1] == pytest.approx(di_felice(0.45, 0.02, 2 * R), rel=1e-12)
    # a per-body value takes precedence; removed, the field gives way to 1
    sim.coupling.set_void_fractions([0.6, 0.6])
    sim.step()
    np.testing.assert_allclose(sim.coupling.fluid_force[:, 2], di_felice(0.6, 0.02, 2 * R), rtol=1e-12)
    sim.coupling.clear()
    sim.coupling.set_void_fraction_field(None, None, None)
    sim.step()
    np.testing.assert_allclose(sim.coupling.fluid_force[:, 2], di_felice(1.0, 0.02, 2 * R), rtol=1e-12)


def test_bad_fields_are_refused(tmp_path):
    dry = balls(tmp_path, FIXED)
    with pytest.raises(ValueError, match="no fluid"):
        dry.coupling.set_void_fraction_field([0, 0, 0], [1, 1, 1], np.full((1, 1, 1), 0.5))
    sim = balls(tmp_path, FIXED, f'[fluid]\ndensity = {RHO_F}\nviscosity = {MU}\n')
    with pytest.raises(ValueError, match=r"shape \(n0, n1, n2, 3\), got \[2, 2, 2\]"):
        sim.coupling.set_fluid_velocity_grid([0, 0, 0], [1, 1, 1], np.zeros((2, 2, 2)))
    with pytest.raises(ValueError, match="spacing along x must be > 0"):
        sim.coupling.set_fluid_velocity_grid([0, 0, 0], [0, 1, 1], np.zeros((2, 2, 2, 3)))
    with pytest.raises(ValueError, match="not finite"):
        sim.coupling.set_fluid_velocity_grid([0, 0, 0], [1, 1, 1], np.full((2, 2, 2, 3), np.inf))
    with pytest.raises(ValueError, match=r"cell 1 must be in \(0, 1\]"):
        sim.coupling.set_void_fraction_field([0, 0, 0], [1, 1, 1], np.array([[[0.5], [1.5]]]))
