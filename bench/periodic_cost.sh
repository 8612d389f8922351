#!/usr/bin/env bash
# What a periodic box costs: the same lattice searched open and with --box 10,10,10 (all axes
# periodic; the lattice fills [0, 10)^3), REPS times each, alternating, openmp on every core.
# Prints CSV: n, m, box, rep, neighbors, grid_s, search_s.
# Usage: bench/periodic_cost.sh BUILD_DIR [SIZES="100"] [SPACINGS="1.5 3.015"] [REPS=3]
set -eu
bin="$1/bin/horizon"
echo "n,m,box,rep,neighbors,grid_s,search_s"
for n in ${SIZES:-100}; do
  for m in ${SPACINGS:-1.5 3.015}; do
    h=$(python3 -c "print($m * 10 / $n)")
    for rep in $(seq "${REPS:-3}"); do
      for box in open periodic; do
        "$bin" search "lattice:$n" --horizon "$h" --backend openmp $([ "$box" = open ] || echo --box 10,10,10) --json \
          | python3 -c "import json,sys; r=json.load(sys.stdin); s=r['seconds']; print(f\"$n,$m,$box,$rep,{r['neighbors']},{s['grid']:.4f},{s['search']:.4f}\")"
      done
    done
  done
done
