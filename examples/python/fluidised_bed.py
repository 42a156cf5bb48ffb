"""CFD-DEM coupling: a bed of glass beads fluidised by water, with a 1-D
fluid solver written here in Python and coupled to Clump through
``sim.coupling``.

300 frictionless glass spheres (d = 1 mm, 2500 kg/m^3; E softened to
1 MPa for a longer time step) settle into a dense random packing on the
floor of a column with periodic sides (6 x 6 mm), about 8 mm deep. Water then flows up through it at a
superficial velocity U that is raised step by step. The fluid solver is
the steady 1-D form of the two-fluid momentum balance ("model A" of
CFD-DEM, Zhou et al. 2010) on horizontal layers of 2 mm, solved every 50
DEM steps:

- the void fraction eps_k of each layer from Clump's grid (theory T-69);
- the interstitial velocity u_k = U / eps_k (continuity at constant U);
- each body gets the eps and u of its layer (Clump then computes the
  Gidaspow drag, T-64, and buoyancy);
- the drag D_k on the bodies of layer k carries the fluid's excess
  pressure gradient: eps_k (-dp/dz)_k A dz = D_k;
- each body gets the pressure-gradient force V_b (-dp/dz)_k as a
  persistent external force;
- the bed's pressure drop is dP = sum_k (-dp/dz)_k dz.

What it shows (printed, and plotted in OUTDIR/fluidised_bed.png):
dP rises with U through the packed bed (Ergun's regime) and levels off at
the bed's buoyant weight per area, W'/A = N (rho_p - rho_f) V g / A, once
the bed is fluidised: the floor then carries nothing. The minimum
fluidisation velocity U_mf, where the fixed-bed curve meets W'/A, is
compared with Wen & Yu's (1966) correlation,
Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7, and with Ergun's equation at
the bed's own void fraction.

    python examples/python/fluidised_bed.py [OUTDIR]

CLUMP_EXAMPLE_SHORT=1 runs fewer and shorter flow steps (what the tests
run). Writes OUTDIR/fluidised_bed.png and OUTDIR/fluidised_bed.csv
(default out/python_fluidised_bed).
"""

import math
import os
import sys

try:
    import matplotlib
except ImportError:
    sys.exit("this example draws its plot with matplotlib: pip install matplotlib")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import clump  # noqa: E402

D = 0.001  # sphere diameter, m
RHO_P, RHO_F, MU, G = 2500.0, 1000.0, 1e-3, 9.81  # glass in water, SI
SIDE, HEIGHT = 0.006, 0.04  # column cross-section side and height, m
N = 300  # spheres
DZ = 0.002  # fluid layer height, m
NZ = int(round(HEIGHT / DZ))
EVERY = 50  # DEM steps per fluid solve
AREA = SIDE * SIDE
V_B = math.pi * D**3 / 6

SCENARIO = f"""
[simulation]
dt = "auto"
dt_fraction = 0.25
gravity = [0.0, 0.0, -{G}]
# a bed lifted from rest gains kinetic energy by orders of magnitude within
# a few steps: that is the flow, not an instability
kinetic_energy_jump = 1e12

[domain]
lo = [0.0, 0.0, -0.002]
hi = [{SIDE}, {SIDE}, {HEIGHT}]
periodic = ["x", "y"]

[[material]]
name = "glass"
youngs_modulus = 1e6
poisson_ratio = 0.25
density = {RHO_P}

[contact]
restitution = 0.5
friction = 0.0

[[template]]
name = "bead"
material = "glass"
shape = "sphere"
radius = {D / 2}

[[mix]]
name = "beads"
[[mix.component]]
template = "bead"
fraction = 1.0

[[wall]]
name = "floor"
material = "glass"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[stage]]
name = "bed"
duration = 1000.0

[[insert]]
kind = "pack"
stage = "bed"
mix = "beads"
count = {N}
region = {{ type = "box", lo = [0.0, 0.0, 0.0005], hi = [{SIDE}, {SIDE}, 0.03] }}
seed = 3

[fluid]
density = {RHO_F}
viscosity = {MU}
drag = "gidaspow"
buoyancy = true
"""


class Column:
    """The 1-D fluid solver: layers of DZ over the column height."""

    def __init__(self, sim):
        self.sim = sim
        self.dp = 0.0  # excess pressure drop over the column, Pa
        self.eps = np.ones(NZ)

    def solve(self, u_sup: float) -> None:
        """Reads the bodies, sets the fluid at each and the pressure force."""
        c = self.sim.coupling
        eps = c.void_fraction([0.0, 0.0, 0.0], [SIDE, SIDE, DZ], (1, 1, NZ),
                              periodic=(True, True, False))[0, 0, :]
        self.eps = np.clip(eps, 0.3, 1.0)
        z = self.sim.bodies.position[:, 2]
        k = np.clip((z / DZ).astype(int), 0, NZ - 1)
        eps_b = self.eps[k]
        # the drag of the last step (fluid force less buoyancy) per layer
        drag = c.fluid_force[:, 2] - RHO_F * V_B * G
        d_k = np.bincount(k, weights=drag, minlength=NZ)
        grad = d_k / (self.eps * AREA * DZ)  # -dp/dz beyond hydrostatic, Pa/m
        self.dp = float(np.sum(grad) * DZ)
        u = np.zeros((len(z), 3))
        u[:, 2] = u_sup / eps_b
        c.set_void_fractions(eps_b)
        c.set_fluid_velocity(u)
        load = np.zeros((len(z), 3))
        load[:, 2] = V_B * grad[k]
        c.set_external_loads(load)


def wen_yu_umf() -> float:
    """Wen & Yu (1966): minimum fluidisation velocity, m/s."""
    ar = D**3 * RHO_F * (RHO_P - RHO_F) * G / MU**2
    return (math.sqrt(33.7**2 + 0.0408 * ar) - 33.7) * MU / (RHO_F * D)


def ergun_dp(u_sup: float, eps: float) -> float:
    """Ergun's pressure drop over a bed of N spheres at void fraction eps, Pa."""
    length = N * V_B / ((1 - eps) * AREA)
    return length * (150 * MU * (1 - eps) ** 2 * u_sup / (eps**3 * D**2)
                     + 1.75 * RHO_F * (1 - eps) * u_sup**2 / (eps**3 * D))


def bisect(f, lo: float, hi: float) -> float:
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def main() -> None:
    short = os.environ.get("CLUMP_EXAMPLE_SHORT") == "1"
    out = sys.argv[1] if len(sys.argv) > 1 else "out/python_fluidised_bed"
    os.makedirs(out, exist_ok=True)
    sim = clump.Simulation.from_toml(SCENARIO)
    col = Column(sim)
    dt = sim.dt
    settle = 0.25
    for _ in range(int(settle / dt) // EVERY):
        col.solve(0.0)
        sim.run(steps=EVERY)
    weight = N * (RHO_P - RHO_F) * V_B * G / AREA  # W'/A, Pa
    # the settled bed's void fraction: the mean over its interior (0.25 mm
    # layers from 1.5 d above the floor to 1.5 d below the top sphere),
    # away from the floor's wall effect and the rough surface
    top = sim.bodies.position[:, 2].max() + D / 2
    fine = sim.coupling.void_fraction([0.0, 0.0, 0.0], [SIDE, SIDE, 0.00025], (1, 1, 160),
                                      periodic=(True, True, False))[0, 0, :]
    zc = (np.arange(160) + 0.5) * 0.00025
    eps_bed = float(np.mean(fine[(zc > 1.5 * D) & (zc < top - 1.5 * D)]))
    u_wy = wen_yu_umf()
    fractions = [0.3, 0.6, 1.4, 1.8] if short else [0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.7, 2.0]
    hold = 0.12 if short else 0.3
    rows = []
    for f in fractions:
        u_sup = f * u_wy
        dps, floor = [], []
        n = int(hold / dt) // EVERY
        for i in range(n):
            col.solve(u_sup)
            sim.run(steps=EVERY)
            if i >= n // 2:  # the second half: steady
                dps.append(col.dp)
                floor.append(sim.walls["floor"].force[2])
        height = np.percentile(sim.bodies.position[:, 2], 98) + D / 2
        rows.append((u_sup, np.mean(dps), -np.mean(floor) / AREA, height))
        print(f"U = {u_sup * 1e3:.3f} mm/s: dP = {rows[-1][1]:.2f} Pa "
              f"(W'/A = {weight:.2f} Pa), floor {rows[-1][2]:.2f} Pa, bed top {height * 1e3:.2f} mm")
    rows = np.array(rows)
    np.savetxt(os.path.join(out, "fluidised_bed.csv"), rows, delimiter=",",
               header="U[m/s],dP[Pa],floor_load_per_area[Pa],bed_top[m]", comments="")
    # U_mf: the fixed-bed points (dP below 80 % of W'/A) fitted by
    # dP = a U + b U^2 (Ergun's form), met with the plateau W'/A
    fixed = rows[rows[:, 1] < 0.8 * weight]
    a, b = np.linalg.lstsq(np.stack([fixed[:, 0], fixed[:, 0] ** 2], axis=1), fixed[:, 1],
                           rcond=None)[0]
    u_mf = bisect(lambda u: a * u + b * u * u - weight, 0.0, 10 * u_wy)
    u_ergun = bisect(lambda u: ergun_dp(u, eps_bed) - weight, 0.0, 10 * u_wy)
    # fluidised: the floor carries less than 1 % of the bed's weight
    plateau = rows[rows[:, 2] < 0.01 * weight]
    print(f"settled bed: void fraction {eps_bed:.3f} (interior), top {top * 1e3:.2f} mm")
    print(f"fixed bed: dP at U = {fixed[0, 0] * 1e3:.3f} mm/s: {fixed[0, 1]:.3f} Pa; "
          f"Ergun at eps = {eps_bed:.3f}: {ergun_dp(fixed[0, 0], eps_bed):.3f} Pa")
    print(f"U_mf measured {u_mf * 1e3:.3f} mm/s; Wen-Yu {u_wy * 1e3:.3f} mm/s; "
          f"Ergun at eps = {eps_bed:.3f}: {u_ergun * 1e3:.3f} mm/s")
    for r in plateau:
        print(f"fluidised: U = {r[0] * 1e3:.3f} mm/s = {r[0] / u_mf:.2f} U_mf, "
              f"dP / (W'/A) = {r[1] / weight:.4f}")
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(rows[:, 0] * 1e3, rows[:, 1], "o-", label="Clump + 1-D fluid solver")
    us = np.linspace(0, rows[-1, 0], 100)
    ax.plot(us * 1e3, [min(ergun_dp(u, eps_bed), 2 * weight) for u in us], "--",
            label=f"Ergun, eps = {eps_bed:.3f}")
    ax.axhline(weight, color="k", lw=0.8, label="bed weight per area W'/A")
    ax.axvline(u_wy * 1e3, color="C3", lw=0.8, label="U_mf, Wen-Yu")
    ax.set_xlabel("superficial velocity U [mm/s]")
    ax.set_ylabel("bed pressure drop [Pa]")
    ax.set_ylim(0, 1.5 * weight)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fluidised_bed.png"), dpi=120)


if __name__ == "__main__":
    main()
