#!/usr/bin/env python3
"""Writes ic_N.txt for the shared tetra bed at any N without numpy: the
lattice of ../shared/bench/tetra-bed/make_ic.py's 10k case (121 sites per
layer, spacing 3.6 mm, from z = 3.6 mm up, jitter +-0.05 mm per axis,
uniform random orientations by Shoemake's method), from Python's own
random generator (seed 2024), so not make_ic.py's numbers. Used for the
per-rank memory figures of docs/scaling.md (N = 50 000: 200 000 spheres,
a column 1.49 m tall; give the scenario a ZTOP of 1.6).
Usage: tetra_ic_column.py N"""
import math
import random
import sys

n = int(sys.argv[1])
rng = random.Random(2024)
sp, jit = 3.6e-3, 0.05e-3
xs = [k * sp - 18e-3 for k in range(11)]
rows = []
k = 0
while len(rows) < n:
    z = sp * (k + 1)
    for x in xs:
        for y in xs:
            if len(rows) < n:
                rows.append((x, y, z))
    k += 1
with open(f"ic_{n}.txt", "w") as f:
    f.write("# id xc yc zc qw qx qy qz\n")
    for i, (x, y, z) in enumerate(rows):
        x, y, z = (c + rng.uniform(-jit, jit) for c in (x, y, z))
        u1, u2, u3 = rng.random(), rng.random(), rng.random()
        q = [
            math.sqrt(u1) * math.cos(2 * math.pi * u3),
            math.sqrt(1 - u1) * math.sin(2 * math.pi * u2),
            math.sqrt(1 - u1) * math.cos(2 * math.pi * u2),
            math.sqrt(u1) * math.sin(2 * math.pi * u3),
        ]
        if q[0] < 0:
            q = [-c for c in q]
        f.write(f"{i + 1} {x:.9e} {y:.9e} {z:.9e} " + " ".join(f"{c:.12f}" for c in q) + "\n")
print(n, "clumps, layers", k, "top", rows[-1][2])
