"""A fixed packed bed against Ergun (1952): spheres held in place in a box,
water flowing up through them at superficial velocity U, the Gidaspow law
(its Ergun branch, eps <= 0.8) at the bed's measured void fraction.

In the two-fluid momentum balance of a fixed bed (the "model A" of
CFD-DEM: Zhou et al. 2010), the fluid's pressure gradient is carried by
the drag and the pressure-gradient force on the particles together:
eps (-dp/dz) = f_drag per bed volume. Ergun gives -dp/dz; Gidaspow's
coefficient is built so that the drag per bed volume equals eps times it.
The test sums the drag Clump computes on every sphere and compares
sum F_z / (A L) with eps * Ergun's dp/L, with the void fraction measured
on Clump's grid (T-69) and checked against the spheres' volume. Both are
the same closed form evaluated two ways (per sphere and summed by Clump, per
bed volume here), so the tolerance is rounding (1e-10 relative), at two
flow rates: one where Ergun's viscous term dominates (Re_p = 0.1) and one
where the inertial term is 60 % of the drop (Re_p = 40)."""

import math

import numpy as np
import pytest

import clump

D = 0.001  # sphere diameter, m
SIDE, HEIGHT = 0.008, 0.008  # bed cross-section side and height, m
MU, RHO_F = 1e-3, 1000.0  # water


def random_packing(n_target: int, seed: int = 1) -> np.ndarray:
    """Random sequential addition of non-overlapping spheres of diameter D
    wholly inside the bed box (x, y in [0, SIDE], z in [0, HEIGHT])."""
    rng = np.random.default_rng(seed)
    lo, hi = D / 2, np.array([SIDE, SIDE, HEIGHT]) - D / 2
    pts = np.empty((0, 3))
    tries = 0
    while len(pts) < n_target and tries < 200000:
        tries += 1
        p = lo + rng.random(3) * (hi - lo)
        if len(pts) == 0 or np.min(np.sum((pts - p) ** 2, axis=1)) >= (D * 1.0001) ** 2:
            pts = np.vstack([pts, p])
    return pts


def bed(tmp_path) -> tuple[clump.Simulation, int]:
    pts = random_packing(280)
    rows = "".join(f"ball,{x!r},{y!r},{z!r},1\n" for x, y, z in pts.tolist())
    (tmp_path / "bed.csv").write_text("template,x,y,z,driven\n" + rows)
    text = f"""
[simulation]
dt = 1e-5
gravity = [0.0, 0.0, 0.0]

[domain]
lo = [-0.001, -0.001, -0.001]
hi = [{SIDE + 0.001}, {SIDE + 0.001}, {HEIGHT + 0.001}]

[[material]]
name = "glass"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500

[contact]
restitution = 0.5
friction = 0.4

[[template]]
name = "ball"
material = "glass"
spheres = [[0.0, 0.0, 0.0, {D / 2}]]

[[insert]]
kind = "file"
file = "bed.csv"

[[stage]]
name = "flow"
steps = 10

[fluid]
density = {RHO_F}
viscosity = {MU}
drag = "gidaspow"
buoyancy = false
"""
    return clump.Simulation.from_toml(text, base_dir=tmp_path), len(pts)


def ergun(eps: float, u_sup: float) -> float:
    """Ergun (1952): pressure drop per bed length, Pa/m."""
    return (150 * MU * (1 - eps) ** 2 * u_sup / (eps**3 * D**2)
            + 1.75 * RHO_F * (1 - eps) * u_sup**2 / (eps**3 * D))


@pytest.mark.parametrize("u_sup", [1e-4, 0.04])
def test_fixed_bed_drag_matches_ergun(tmp_path, u_sup):
    sim, n = bed(tmp_path)
    eps = sim.coupling.void_fraction([0, 0, 0], [SIDE, SIDE, HEIGHT], (1, 1, 1))[0, 0, 0]
    # every sphere lies wholly in the one cell: the lattice division is exact
    v_solid = n * math.pi * D**3 / 6
    assert eps == pytest.approx(1 - v_solid / (SIDE * SIDE * HEIGHT), rel=1e-12)
    assert 0.55 < eps < 0.8  # Gidaspow's Ergun branch
    sim.coupling.set_void_fractions(np.full(n, eps))
    u = np.zeros((n, 3))
    u[:, 2] = u_sup / eps  # interstitial velocity
    sim.coupling.set_fluid_velocity(u)
    sim.step()
    assert np.all(sim.bodies.velocity == 0.0)  # the bed is held
    drag = sim.coupling.fluid_force[:, 2].sum()
    per_volume = drag / (SIDE * SIDE * HEIGHT)
    re_p = RHO_F * u_sup * D / MU
    print(f"U = {u_sup} m/s, Re_p = {re_p:.3g}, eps = {eps:.4f}: "
          f"sum F/(A L) / eps = {per_volume / eps:.6e} Pa/m, Ergun {ergun(eps, u_sup):.6e} Pa/m")
    assert per_volume == pytest.approx(eps * ergun(eps, u_sup), rel=1e-10)
