#!/usr/bin/env bash
# The cost of ten bond filters (bench/filters/ten_cracks.json) against the unfiltered search of
# lattice 100 at m = 3.015, alternating, on one machine; OLD=<horizon binary> adds an older
# build's filtered run. Prints: run, threads, kind, grid+search s, filter s, entries.
# Usage: bash bench/filters/filter_cost.sh BUILD_DIR [threads...]
build=$1; shift
for threads in "${@:-0}"; do
  for run in 1 2 3; do
    for kind in open new old; do
      bin=$build/bin/horizon; filters=(--bond-filters bench/filters/ten_cracks.json)
      [ "$kind" = open ] && filters=()
      if [ "$kind" = old ]; then [ -n "${OLD:-}" ] || continue; bin=$OLD; fi
      "$bin" search lattice:100 --horizon 0.3015 --backend openmp --threads "$threads" "${filters[@]}" --json --quiet |
        python3 -c "import json,sys; d=json.load(sys.stdin); s=d['seconds']
print('$run,$threads,$kind,%.3f,%.3f,%d' % (s['grid'] + s['search'], s['filter'], d['neighbors']))"
    done
  done
done
