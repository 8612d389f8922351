#!/usr/bin/env bash
# A fresh process's first search (what `make run` and a one-shot CLI user see: page faults
# included) on the GPU machine's host, this tree against .deps/old-src, alternating. Run after
# device_cpu_ab.sh (uses both build-ab trees). Usage: bash bench/gpu/device_cli_first_call.sh
set -u
for tree in . .deps/old-src; do
  cmake --build $tree/build-ab -j "$(nproc)" --target horizon_cli 2>&1 | grep -E "error"
done
for threads in 16 1; do
  for m in 0.15 0.3015; do
    for round in 1 2 3; do
      for tree in . .deps/old-src; do
        echo -n "$tree threads $threads horizon $m: "
        OMP_NUM_THREADS=$threads $tree/build-ab/bin/horizon search lattice:100 --horizon $m --json --quiet
      done
    done
  done
done > $OUT/cli_first_call.jsonl 2>&1
cat $OUT/cli_first_call.jsonl | python3 -c "
import json, sys
for line in sys.stdin:
    tree, rest = line.split(': ', 1)
    d = json.loads(rest); s = d['seconds']
    print(tree, round(d['points_per_second'] / 1e6, 2), 'grid', round(s['grid'], 4), 'search', round(s['search'], 4))"
