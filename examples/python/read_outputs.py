"""Reading a finished run's outputs and plotting them.

Every run (`clump run`, or `clump.Simulation(..., output_dir=...)`) leaves
in its folder: thermo.csv (one row per thermo output, each header naming
its unit), traj_<id>.csv (the bodies asked for), final_state.json (every
body's final state, with exact bit patterns), manifest.json (what ran, how
fast) and VTK frames. This script reads them with the standard library and
numpy and plots the T-handle's Dzhanibekov flip: the body-frame angular
velocity (the spin about the intermediate axis flips again and again) and
the energy, which the no_squish scheme keeps constant.

    python examples/python/read_outputs.py [RUN_DIR]

Without RUN_DIR it first runs examples/t_handle.toml from Python into
out/python_t_handle (the same files `clump run examples/t_handle.toml -o
out/python_t_handle` writes; about 10 s, most of it writing 6000
trajectory rows). CLUMP_EXAMPLE_SHORT=1 runs the first 0.5 s only.
Writes RUN_DIR/summary.png.
"""

import csv
import json
import os
import pathlib
import sys

try:
    import matplotlib
except ImportError:
    sys.exit("this example draws its plot with matplotlib: pip install matplotlib")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent


def make_run(outdir: pathlib.Path, short: bool) -> pathlib.Path:
    import clump

    scenario = HERE.parent / "t_handle.toml"
    text = scenario.read_text()
    if short:
        text = text.replace("duration = 6.0", "duration = 0.5")
    sim = clump.Simulation.from_toml(text, base_dir=scenario.parent, name=scenario.name,
                                     output_dir=outdir, overwrite=True)
    sim.run()
    return outdir


def read_csv(path):
    """A CSV file as {column: numpy array}."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def main():
    short = os.environ.get("CLUMP_EXAMPLE_SHORT") == "1"
    if len(sys.argv) > 1:
        run = pathlib.Path(sys.argv[1])
    else:
        run = make_run(pathlib.Path("out/python_t_handle"), short)
    manifest = json.loads((run / "manifest.json").read_text())
    final = json.loads((run / "final_state.json").read_text())
    thermo = read_csv(run / "thermo.csv")
    print(f"{manifest['scenario']}: {manifest['status']}, {manifest['final_step']} steps, "
          f"t = {manifest['simulated_time']} s, {manifest['bodies']} bodies; "
          f"{manifest['sphere_steps_per_s']:.3g} sphere-steps/s")
    b = final["bodies"][0]
    print(f"body {b['id']} ends at {b['position']} (m)")

    trajs = sorted(run.glob("traj_*.csv"))
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    if trajs:
        tr = read_csv(trajs[0])
        for c in ("wbx", "wby", "wbz"):
            axes[0].plot(tr["time"], tr[c], label=c)
        axes[0].set_ylabel("body-frame ω [rad/s]")
        axes[0].legend(loc="upper right")
    e = thermo["ke_translational[J]"] + thermo["ke_rotational[J]"]
    axes[1].plot(thermo["time[s]"], e, label="kinetic energy")
    axes[1].set_ylabel("energy [J]")
    axes[1].set_xlabel("time [s]")
    drift = (e.max() - e.min()) / e[0] if e[0] else 0.0
    print(f"kinetic energy {e[0]:.6e} J, relative spread {drift:.2e} over the run")
    fig.tight_layout()
    out = run / "summary.png"
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")
    return manifest, thermo


if __name__ == "__main__":
    main()
