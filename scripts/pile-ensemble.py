#!/usr/bin/env python3
"""The stone pile's physics against LIGGGHTS over an ensemble of piles
(docs/performance.md, section 4).

    python3 scripts/pile-ensemble.py [--case stone-pile|stone-mix]
        [--seeds 1,2,3,...] [--threads T] [--liggghts-tangential]

A pile of 200 stones is one sample of a random packing: two piles poured
from starting poses a little apart differ in their contact counts by
several per cent, so one pile's figures cannot tell a modelling difference
of that size from chance. This script pours the pile once per pose seed
with both codes (`clump bench --case C --pose-seed S --liggghts-rounds 1`,
each seed in its own folder under out/pile-ensemble/), reads the physics
lines the bench prints, and reports for each figure both codes' means over
the seeds, their spread, and the mean of the per-seed differences with its
standard error. With `--liggghts-tangential` Clump also pours every seed
with LIGGGHTS' tangential rule (Clump alone; compared with the same seed's
LIGGGHTS pile).

Run from the repository root with the release `clump` built
(target/release/clump, or $CLUMP_BIN) and LIGGGHTS installed
(`apt-get install liggghts liggghts-doc`). Standard library only.
"""

import argparse
import math
import os
import re
import statistics
import subprocess
import sys

FIGURES = ["mean sphere height", "surface", "packing fraction", "sphere contacts", "body contacts"]
LINE = re.compile(
    r"physics (clump|liggghts)\s*: \d+ bodies, mean sphere height (\S+) m, surface (\S+) m, "
    r"packing fraction[^)]*\)? ?(\S+), sphere contacts (\d+), body contacts (\d+)"
)


def pour(clump, case, seed, threads, work, liggghts_tangential):
    """Runs one pile; returns {code: [figures]} from the bench's physics lines."""
    cmd = [clump, "bench", "--case", case, "--pose-seed", str(seed), "--threads", str(threads),
           "--work", work, "--liggghts-rounds", "0" if liggghts_tangential else "1"]
    if liggghts_tangential:
        cmd.append("--liggghts-tangential")
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{run.stderr}")
    found = {}
    for line in run.stdout.splitlines():
        m = LINE.match(line)
        if m:
            found[m.group(1)] = [float(m.group(k)) for k in range(2, 7)]
    if "clump" not in found or (not liggghts_tangential and "liggghts" not in found):
        sys.exit(f"{' '.join(cmd)}: no physics lines in its output (is LIGGGHTS installed?)")
    return found


def summary(label, clump, peer):
    """Prints each figure's means, spreads and mean per-seed difference."""
    print(f"\n{label} (n = {len(clump)} piles)")
    print(f"{'figure':20s} {'Clump mean':>12s} {'sd':>6s} {'LIGGGHTS mean':>14s} {'sd':>6s}"
          f" {'difference of means':>20s} {'s.e.':>7s}")
    for k, name in enumerate(FIGURES):
        a = [c[k] for c in clump]
        b = [p[k] for p in peer]
        ma, mb = statistics.mean(a), statistics.mean(b)
        d = [x - y for x, y in zip(a, b)]
        se = statistics.stdev(d) / math.sqrt(len(d)) if len(d) > 1 else float("nan")
        sa = statistics.stdev(a) / ma * 100 if len(a) > 1 else float("nan")
        sb = statistics.stdev(b) / mb * 100 if len(b) > 1 else float("nan")
        print(f"{name:20s} {ma:12.6g} {sa:5.1f}% {mb:14.6g} {sb:5.1f}%"
              f" {100 * (ma - mb) / mb:+19.2f}% {100 * se / mb:6.2f}%")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="stone-pile", choices=["stone-pile", "stone-mix"])
    ap.add_argument("--seeds", default="1,2,3,4,5,6,7,8,32452843",
                    help="comma-separated pose seeds (default: eight and the bench's own)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--liggghts-tangential", action="store_true",
                    help="also pour every seed with LIGGGHTS' tangential rule in Clump")
    args = ap.parse_args()
    clump = os.environ.get("CLUMP_BIN", "target/release/clump")
    seeds = [int(s) for s in args.seeds.split(",")]
    rows = {"clump": [], "liggghts": [], "clump_lt": []}
    print(f"{'seed':>10s} {'code':10s} " + " ".join(f"{f:>18s}" for f in FIGURES))
    for s in seeds:
        base = f"out/pile-ensemble/{args.case}-{s}"
        got = pour(clump, args.case, s, args.threads, base, False)
        pairs = [("clump", got["clump"]), ("liggghts", got["liggghts"])]
        if args.liggghts_tangential:
            lt = pour(clump, args.case, s, args.threads, base + "-lt", True)
            pairs.append(("clump_lt", lt["clump"]))
        for code, v in pairs:
            rows[code].append(v)
            print(f"{s:10d} {code:10s} " + " ".join(f"{x:18.6g}" for x in v), flush=True)
    summary("Clump (its default tangential rule) against LIGGGHTS", rows["clump"], rows["liggghts"])
    if args.liggghts_tangential:
        summary("Clump with LIGGGHTS' tangential rule against LIGGGHTS", rows["clump_lt"],
                rows["liggghts"])


if __name__ == "__main__":
    main()
