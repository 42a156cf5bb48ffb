#!/bin/bash
# Phase B of the tetra bed on this machine: 1 thread, 2 threads, 2 ranks
# (this build, and optionally a baseline build), alternated rounds, each
# from the same phase-A checkpoint; prints wall s, CPU s (user + sys of
# every process), sphere-steps per wall and per CPU second, the 1-minute
# load average before the run, and whether final_state.json equals the
# 1-thread run's (docs/scaling.md, "Measured").
# usage: rank_speed.sh CHECKPOINT SPHERES ROUNDS OUTDIR BIN [BASE_BIN]
# (STEPS=S in the environment: stop at step S, a part of phase B)
set -u
CK=$1; NS=$2; ROUNDS=$3; OUT=$4; BIN=$5; BASE=${6:-}
LIMIT=${STEPS:+--steps $STEPS}
MPI="mpirun --oversubscribe --allow-run-as-root -np 2"
mkdir -p "$OUT"
variants="t1 t2 r2"
[ -n "$BASE" ] && variants="$variants r2base"
for r in $(seq 1 "$ROUNDS"); do
  for v in $variants; do
    d="$OUT/$v-$r"; rm -rf "$d"
    load=$(cut -d' ' -f1 /proc/loadavg)
    case $v in
      t1) cmd="$BIN resume $CK -o $d $LIMIT --threads 1" ;;
      t2) cmd="$BIN resume $CK -o $d $LIMIT --threads 2" ;;
      r2) cmd="$MPI $BIN resume $CK -o $d $LIMIT --threads 1" ;;
      r2base) cmd="$MPI $BASE resume $CK -o $d $LIMIT --threads 1" ;;
    esac
    /usr/bin/time -f "%e %U %S" -o "$d.time" $cmd > "$d.log" 2>&1
    read -r wall user sys < "$d.time"
    run_wall=$(grep -o 'wall time [0-9.]* s' "$d.log" | awk '{print $3}')
    steps=$(grep -o '([0-9]* steps' "$d.log" | head -1 | tr -d '(' | awk '{print $1}')
    same=$(cmp -s "$d/final_state.json" "$OUT/t1-$r/final_state.json" && echo same || echo DIFFERENT)
    awk -v v=$v -v r=$r -v w="$run_wall" -v c="$user $sys" -v n=$NS -v s="$steps" -v l=$load -v same=$same \
      'BEGIN{split(c,a," "); cpu=a[1]+a[2]; printf "round %d %-7s load %5.2f  wall %7.2f s  cpu %7.2f s  %6.3f M sphere-steps/s wall  %6.3f M per CPU s  final_state %s\n", r, v, l, w, cpu, n*s/w/1e6, n*s/cpu/1e6, same}'
  done
done
