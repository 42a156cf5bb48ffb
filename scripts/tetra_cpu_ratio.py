"""Phase-B CPU seconds of Clump and LIGGGHTS, round by round, and their
ratio (docs/performance.md, section 2, "CPU time").

    python3 scripts/tetra_cpu_ratio.py out/tetra.log out/liggghts-cpu.log [NB_STEPS [SPHERES]]

The first file is the output of `clump bench --liggghts-rounds R` (its
"CPU time ... phase B X s" lines, one per Clump round); the second, the log
that scripts/liggghts-cpu/liggghts wrote during the same bench (the
LIGGGHTS process's CPU time at the start and the end of each run; phase B
is the run of NB_STEPS steps, default 10000; SPHERES default 8000).
"""
import re
import sys

log, cpulog = sys.argv[1], sys.argv[2]
nb_steps = int(sys.argv[3]) if len(sys.argv) > 3 else 10000
spheres = int(sys.argv[4]) if len(sys.argv) > 4 else 8000
clump = [float(m.group(1)) for m in re.finditer(r"phase B ([\d.]+) s \(", open(log).read())]
procs = {}
for line in open(cpulog):
    m = re.match(r"\S+ pid (\d+) cpu_s (\d+)/(\d+) :: (.*)", line)
    if m:
        procs.setdefault(m.group(1), []).append((int(m.group(2)) / int(m.group(3)), m.group(4)))
lig = []
for events in procs.values():
    for k, (cpu, text) in enumerate(events):
        if (
            text.startswith("Loop time")
            and f"for {nb_steps} steps" in text
            and k > 0
            and events[k - 1][1].startswith("Setting up")
        ):
            lig.append(cpu - events[k - 1][0])
ratios = []
for r, (c, g) in enumerate(zip(clump, lig)):
    ratios.append(g / c)
    print(
        f"round {r}: clump phase B CPU {c:.2f} s ({nb_steps * spheres / c / 1e6:.2f} M/CPU-s), "
        f"liggghts {g:.2f} s ({nb_steps * spheres / g / 1e6:.2f} M/CPU-s), ratio {g / c:.2f}"
    )
s = sorted(ratios)
if s:
    n = len(s)
    med = s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])
    print(f"median of {n}: {med:.2f}")
