#!/usr/bin/env python3
"""Reference sums for the exact accumulator's test (crates/clump-core/tests/exact_sum.rs).

Writes crates/clump-core/tests/fixtures/exact_sum_cases.txt: one case per
line, the terms' IEEE bit patterns (hex) and then, after ';', the bits of
their real sum rounded to the nearest double (ties to even), computed with
Python's exact rationals (fractions.Fraction; int / int division rounds
correctly) and checked against math.fsum. Adversarial cases: cancellation
across the whole exponent range, exact halfway ties, subnormals, long runs
of tiny terms under a large one, random terms of every exponent.
"""
import math
import random
import struct
from fractions import Fraction
from pathlib import Path

def bits(x):
    return struct.unpack("<Q", struct.pack("<d", x))[0]

def exact(terms):
    s = sum((Fraction(t) for t in terms), Fraction(0))
    r = float(s) if s != 0 else 0.0
    assert r == math.fsum(terms) or (r == 0 and math.fsum(terms) == 0), terms
    return r

rng = random.Random(57)
tiny = 2.0 ** -1074
cases = [
    [1e308, 1.0, -1e308],
    [2.0 ** 53, 1.0],                      # halfway: ties to even (down)
    [2.0 ** 53 + 2, 1.0],                  # halfway: ties to even (up)
    [2.0 ** 53, 1.0, tiny],                # just above halfway: up
    [2.0 ** 53, 1.0, -tiny],               # just below halfway: down
    [tiny] * 300,                          # subnormals only
    [2.0 ** -1022, -tiny],                 # normal minus subnormal
    [1.0] + [2.0 ** -60] * 3000,           # many terms under one ulp each
    [1.7976931348623157e308, -1.7976931348623157e308, 5e-324],
    [0.1, 0.2, 0.3],
    [1e16, 1.0, -1e16, 1e-16],
    [-0.5, -2.0 ** -54],
]
for _ in range(200):
    n = rng.randint(1, 60)
    t = []
    for _ in range(n):
        e = rng.randint(-1074, 1000)
        m = rng.uniform(-1, 1)
        t.append(math.ldexp(m, e) if e > -1022 else m * 2.0 ** -1022)
    # cancellation: add the negatives of some terms and a few tiny ones
    t += [-x for x in rng.sample(t, rng.randint(0, len(t)))]
    t += [math.ldexp(rng.uniform(-1, 1), rng.randint(-1074, -900)) for _ in range(rng.randint(0, 5))]
    rng.shuffle(t)
    cases.append(t)

out = Path(__file__).resolve().parent.parent / "crates/clump-core/tests/fixtures/exact_sum_cases.txt"
with open(out, "w") as f:
    f.write("# terms (IEEE bits, hex) ; their real sum rounded to nearest even (scripts/exact_sum_cases.py)\n")
    for t in cases:
        f.write(" ".join(f"{bits(x):016x}" for x in t) + f" ; {bits(exact(t)):016x}\n")
print(f"{len(cases)} cases -> {out}")
