#!/usr/bin/env python3
"""Speed of the Python package against `clump run` (docs/python.md).

    python scripts/bench-python.py [--steps N] [--rounds K]

Run from the repository root with the package installed and the release
`clump` binary built (target/release/clump, or $CLUMP_BIN); needs the shared
benchmark folder ../shared/bench/tetra-bed. Prints:
  1. the tetra-bed benchmark (2000 four-sphere clumps) for N steps:
     `clump run --steps N` (its manifest's loop wall time) and
     `Simulation.from_file(...).run(steps=N)` with the same output folder
     work, and without outputs; rounds alternate CLI and Python;
  2. the cost of one callback call (a no-op callback at every step of a
     one-body run, against the same run without);
  3. the cost of each accessor and setter with 10⁵ bodies.
"""

import argparse
import json
import os
import resource
import pathlib
import statistics
import subprocess
import tempfile
import time

import numpy as np

import clump

REPO = pathlib.Path(__file__).resolve().parents[1]
CLUMP = os.environ.get("CLUMP_BIN", str(REPO / "target" / "release" / "clump"))


def cpu_self():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def bench_run(steps, rounds):
    """Wall time of the stepping loop (the CLI's manifest `wall_time_s`,
    Python's `run` call) and CPU time (user + system, all threads) of the
    whole job (set-up, stepping, output), which a loaded machine disturbs
    less."""
    sc = REPO / "benches" / "tetra_bed_2000.toml"
    res = {k: [] for k in ("cli", "py", "bare", "cli_cpu", "py_cpu", "bare_cpu")}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for k in range(rounds):
            out = tmp / f"cli{k}"
            c = cpu_children()
            subprocess.run([CLUMP, "run", str(sc), "-o", str(out), "--steps", str(steps)],
                           check=True, capture_output=True, cwd=REPO)
            res["cli_cpu"].append(cpu_children() - c)
            res["cli"].append(json.loads((out / "manifest.json").read_text())["wall_time_s"])
            for key, outdir in (("py", tmp / f"py{k}"), ("bare", None)):
                c = cpu_self()
                sim = clump.Simulation.from_file(sc, output_dir=outdir)
                t = time.perf_counter()
                sim.run(steps=steps)
                res[key].append(time.perf_counter() - t)
                if outdir is not None:
                    sim.save_checkpoint(outdir / "last.ckpt")  # as clump run --steps does
                res[key + "_cpu"].append(cpu_self() - c)
                del sim

    def show(name, v):
        print(f"  {name:44s} median {statistics.median(v):7.3f} s  (runs: "
              + ", ".join(f"{x:.3f}" for x in v) + ")")
    print(f"1. tetra_bed_2000, {steps} steps, {rounds} rounds (alternating)")
    show("clump run --steps N: loop wall time", res["cli"])
    show("Python run(steps=N), same outputs: wall", res["py"])
    show("Python run(steps=N), no output folder: wall", res["bare"])
    show("clump run --steps N: CPU of the job", res["cli_cpu"])
    show("Python, same outputs: CPU of the job", res["py_cpu"])
    show("Python, no output folder: CPU of the job", res["bare_cpu"])
    for a, b in (("py", "cli"), ("py_cpu", "cli_cpu")):
        r = statistics.median(res[a]) / statistics.median(res[b]) - 1
        print(f"  Python with outputs vs clump run ({a} / {b}, medians): {r:+.1%}")


def bench_callback(steps=20000, rounds=5):
    sc = REPO / "examples" / "t_handle.toml"
    plain, cb = [], []
    for _ in range(rounds):
        s = clump.Simulation.from_file(sc)
        t = time.perf_counter()
        s.run(steps=steps)
        plain.append(time.perf_counter() - t)
        s = clump.Simulation.from_file(sc)
        t = time.perf_counter()
        s.run(steps=steps, callback=lambda sim: None, every=1)
        cb.append(time.perf_counter() - t)
        s = clump.Simulation.from_file(sc)
    per = (statistics.median(cb) - statistics.median(plain)) / steps
    print(f"2. callback: one body (t_handle), {steps} steps: without {statistics.median(plain):.3f} s, "
          f"no-op callback at every step {statistics.median(cb):.3f} s -> {per * 1e6:.2f} µs per call")


def bench_accessors(n=100_000, reps=20):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        side = int(np.ceil(n ** (1 / 3)))
        idx = np.arange(n)
        xyz = np.stack([idx % side, (idx // side) % side, idx // side ** 2], axis=1) * 0.003
        with open(tmp / "bodies.csv", "w") as f:
            f.write("template,x,y,z\n")
            for x, y, z in xyz:
                f.write(f"ball,{x:.4f},{y:.4f},{z:.4f}\n")
        (tmp / "s.toml").write_text(f"""
[simulation]
dt = 1e-5
gravity = [0.0, 0.0, 0.0]
duration = 0.01
[domain]
lo = [-0.01, -0.01, -0.01]
hi = [{side * 0.003 + 0.01}, {side * 0.003 + 0.01}, {side * 0.003 + 0.01}]
[[material]]
name = "m"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500
[[template]]
name = "ball"
material = "m"
spheres = [[0.0, 0.0, 0.0, 0.001]]
[[insert]]
kind = "file"
file = "bodies.csv"
""")
        sim = clump.Simulation.from_file(tmp / "s.toml")
        sim.run(steps=2)
        b, s = sim.bodies, sim.spheres
        print(f"3. accessors with {len(b)} bodies ({len(s)} spheres), median of {reps} calls:")
        v, q, w = b.velocity, b.quaternion, b.omega
        cases = [
            ("bodies.id", lambda: b.id), ("bodies.mass", lambda: b.mass),
            ("bodies.position", lambda: b.position), ("bodies.velocity", lambda: b.velocity),
            ("bodies.quaternion", lambda: b.quaternion), ("bodies.omega", lambda: b.omega),
            ("bodies.omega_body", lambda: b.omega_body), ("bodies.force", lambda: b.force),
            ("spheres.position", lambda: s.position), ("spheres.radius", lambda: s.radius),
            ("contacts()", sim.contacts), ("thermo()", sim.thermo),
            ("bodies.velocity = v", lambda: setattr(b, "velocity", v)),
            ("bodies.quaternion = q", lambda: setattr(b, "quaternion", q)),
            ("bodies.omega = w", lambda: setattr(b, "omega", w)),
        ]
        for name, f in cases:
            ts = []
            for _ in range(reps):
                t = time.perf_counter()
                f()
                ts.append(time.perf_counter() - t)
            print(f"  {name:24s} {statistics.median(ts) * 1e3:8.2f} ms")


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=5000)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    bench_run(a.steps, a.rounds)
    bench_callback()
    bench_accessors()
