"""Co-simulation: a servo-controlled piston compresses a granular bed to a
target pressure, the controller running in Python between steps.

60 tetrahedral clumps settle in a square box (4 × 4 cm); then the piston,
a plane wall facing down, is driven by a proportional controller that reads
the force the particles exert on it every 2 ms of simulated time and sets
its velocity:

    v_z = −clip(gain · (p_target − p) / p_target, −v_max, v_max),   p = F_z / A

so the piston moves down while the pressure is low and backs off when it
overshoots (before it first touches the bed it approaches at 0.2 m/s). The plot shows the pressure reaching the target and holding it.

    python examples/python/servo_piston.py [OUTDIR]

CLUMP_EXAMPLE_SHORT=1 runs a shorter compression (what the tests run).
Writes OUTDIR/servo.png and OUTDIR/servo.csv (default out/python_servo).
"""

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

HALF = 0.02  # box half width, m
AREA = (2 * HALF) ** 2  # piston area, m²
P_TARGET = 2000.0  # Pa
V_MAX = 0.05  # m/s, servo speed limit
V_APPROACH = 0.2  # m/s, until the piston touches the bed
GAIN = 0.05  # m/s at a pressure error of 100 %

SCENARIO = f"""
[simulation]
dt = 4e-5
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.03, -0.03, -0.01]
hi = [0.03, 0.03, 0.12]

[[material]]
name = "grain"
youngs_modulus = 5e6
poisson_ratio = 0.3
density = 2500

[[material]]
name = "steel"
youngs_modulus = inf
poisson_ratio = 0.3
density = 0

[contact]
restitution = 0.3
friction = 0.4

[[template]]
name = "tetra"
material = "grain"
shape = "tetrahedron"
radius = 0.002
edge = 0.003

[[wall]]
name = "box"
material = "steel"
type = "box"
lo = [{-HALF}, {-HALF}, 0.0]
hi = [{HALF}, {HALF}, 0.11]

[[wall]]
name = "piston"
material = "steel"
type = "plane"
point = [0.0, 0.0, 0.041]
normal = [0.0, 0.0, -1.0]

[[insert]]
kind = "pack"
template = "tetra"
count = 60
region = {{ type = "box", lo = [-0.017, -0.017, 0.003], hi = [0.017, 0.017, 0.04] }}
seed = 7

[[stage]]
name = "settle"
duration = 0.15

[[stage]]
name = "servo"
duration = {{servo}}

[output]
thermo = {{ every = 0.01 }}
"""


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else "out/python_servo"
    os.makedirs(outdir, exist_ok=True)
    short = os.environ.get("CLUMP_EXAMPLE_SHORT") == "1"
    servo_time = 0.25 if short else 0.6
    sim = clump.Simulation.from_toml(SCENARIO.replace("{servo}", str(servo_time)),
                                     name="servo_piston.toml")
    sim.run(time=0.15)  # settle, piston at rest
    top = (sim.spheres.position[:, 2] + sim.spheres.radius).max()
    print(f"settled: bed top at {top * 1e3:.1f} mm, piston at {sim.walls['piston'].center[2] * 1e3:.1f} mm")
    piston = sim.walls["piston"]
    history = []

    def servo(s):
        p = piston.force[2] / AREA  # particles push the piston up: F_z > 0
        err = (P_TARGET - p) / P_TARGET
        if p == 0.0 and not history:  # not touched yet: approach
            vz = -V_APPROACH
        else:
            vz = -float(np.clip(GAIN * err, -V_MAX, V_MAX))
            history.append((s.time, p, piston.center[2], vz))
        piston.velocity = [0.0, 0.0, vz]

    sim.run(callback=servo, every=50)  # every 50 steps = 2 ms
    t, p, z, v = map(np.array, zip(*history))
    np.savetxt(os.path.join(outdir, "servo.csv"), np.column_stack([t, p, z, v]), delimiter=",",
               header="time[s],pressure[Pa],piston_z[m],piston_vz[m/s]", comments="")
    late = p[t > t[-1] - 0.05]
    print(f"{len(history)} controller calls; pressure over the last 50 ms: "
          f"{late.mean():.0f} Pa (target {P_TARGET:.0f} Pa), spread {late.std():.0f} Pa")
    fig, (a, b) = plt.subplots(2, 1, sharex=True, figsize=(6, 5))
    a.plot(t, p, label="pressure on the piston")
    a.axhline(P_TARGET, color="k", ls="--", label="target")
    a.set_ylabel("pressure [Pa]")
    a.legend()
    b.plot(t, z * 1e3)
    b.set_ylabel("piston height [mm]")
    b.set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "servo.png"), dpi=120)
    print(f"wrote {os.path.join(outdir, 'servo.png')}")
    return t, p


if __name__ == "__main__":
    main()
