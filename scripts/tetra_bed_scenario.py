#!/usr/bin/env python3
"""Writes the shared tetra bed (../shared/bench/tetra-bed) as a Clump
scenario: tetra_N.toml in the current folder, reading ic_N.txt (copy it
here) through kind = "file", format = "xyzq", orientation_frame = "input";
five planes; phase A (40 000 steps) and B (10 000) as two stages.
Usage: tetra_bed_scenario.py N ZTOP TETRA_XYZR   (docs/scaling.md)"""
import sys

n, ztop, xyzr = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
rows = [l.split() for l in open(xyzr) if l.strip() and not l.startswith("#")]
spheres = ",\n  ".join("[%s, %s, %s, %s]" % tuple(r) for r in rows)
walls = "".join(
    f'''
[[wall]]
name = "{name}"
material = "m"
type = "plane"
point = {point}
normal = {normal}
'''
    for name, point, normal in [
        ("floor", "[0.0, 0.0, 0.0]", "[0.0, 0.0, 1.0]"),
        ("xlo", "[-0.02, 0.0, 0.0]", "[1.0, 0.0, 0.0]"),
        ("xhi", "[0.02, 0.0, 0.0]", "[-1.0, 0.0, 0.0]"),
        ("ylo", "[0.0, -0.02, 0.0]", "[0.0, 1.0, 0.0]"),
        ("yhi", "[0.0, 0.02, 0.0]", "[0.0, -1.0, 0.0]"),
    ]
)
open(f"tetra_{n}.toml", "w").write(f'''# the shared tetra bed, {n} clumps, phases A and B
[simulation]
dt = 1e-5
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.02, -0.02, 0.0]
hi = [0.02, 0.02, {ztop}]

[[material]]
name = "m"
youngs_modulus = 5e6
poisson_ratio = 0.3
density = 2500

[contact]
restitution = 0.5
friction = 0.5

[[template]]
name = "tetra"
material = "m"
spheres = [
  {spheres}
]
{walls}
[[stage]]
name = "A"
steps = 40000

[[stage]]
name = "B"
steps = 10000

[[insert]]
kind = "file"
stage = "A"
file = "ic_{n}.txt"
format = "xyzq"
template = "tetra"
orientation_frame = "input"

[output]
thermo = {{ every = 0.1 }}
''')
