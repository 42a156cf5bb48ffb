#!/usr/bin/env python3
"""A half-dense box for the balance measurement of docs/scaling.md
("Balance on counted cost"): writes ic_uneven.txt (tetra clumps on a
lattice of spacing 3.6 mm for x < 0.1 m and 7.2 mm beyond, random
orientations from Python's generator, seed 7) and uneven.toml (at rest,
no gravity, fixed skin 0.8 mm). Usage: uneven_box_ic.py TETRA_XYZR
(../shared/bench/tetra-bed/tetra.xyzr); then
mpirun -np 4 clump run uneven.toml -o D --steps 300 --threads 1"""
import math, os, random, subprocess, sys
xyzr = sys.argv[1]
rng = random.Random(7)
rows = []
def lattice(x0, x1, sp):
    n = int((0.04 - sp / 2) / sp) + 1
    x = x0 + sp / 2
    while x < x1:
        for j in range(n):
            for k in range(n):
                rows.append((x, sp / 2 + j * sp, sp / 2 + k * sp))
        x += sp
lattice(0.0, 0.1, 3.6e-3)
lattice(0.1, 0.3 - 3.6e-3, 7.2e-3)
with open("ic_uneven.txt", "w") as f:
    f.write("# id xc yc zc qw qx qy qz\n")
    for i, (x, y, z) in enumerate(rows):
        u1, u2, u3 = rng.random(), rng.random(), rng.random()
        q = [math.sqrt(u1) * math.cos(2 * math.pi * u3), math.sqrt(1 - u1) * math.sin(2 * math.pi * u2),
             math.sqrt(1 - u1) * math.cos(2 * math.pi * u2), math.sqrt(u1) * math.sin(2 * math.pi * u3)]
        f.write(f"{i+1} {x:.9e} {y:.9e} {z:.9e} " + " ".join(f"{c:.12f}" for c in q) + "\n")
print(len(rows))
# the material and template of the shared tetra bed, from its scenario
# writer (one clump, removed again)
here = os.path.dirname(os.path.abspath(__file__))
subprocess.run([sys.executable, os.path.join(here, "tetra_bed_scenario.py"), "1", "1.0", xyzr], check=True)
bed = open("tetra_1.toml").read()
os.remove("tetra_1.toml")
parts = bed[bed.index("[[material]]"):bed.index("[[wall]]")]
open("uneven.toml", "w").write('''# half-dense box at rest (docs/scaling.md, "Balance on counted cost")
[simulation]
dt = 1e-5
gravity = [0.0, 0.0, 0.0]
skin = 0.8e-3

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.3, 0.04, 0.04]

''' + parts + '''[[insert]]
kind = "file"
stage = "A"
file = "ic_uneven.txt"
format = "xyzq"
template = "tetra"
orientation_frame = "input"

[[stage]]
name = "A"
steps = 100000

[output]
thermo = { every = 1.0 }
''')
