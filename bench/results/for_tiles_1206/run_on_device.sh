#!/usr/bin/env bash
# One device call, CPU only: the fill's tiles dispatched by ForTiles<tile> (this tree) against
# .deps/old-src (= 435c7d3, its own 4/2/1 dispatch), built on the GPU machine's 16-core host;
# the search's oracle tests; the count and fill passes alone (../cpu_phases_1205/phase_bench.cpp,
# min of 3 reps), trees alternating, three rounds.
# Usage (device, .deps carried): bash bench/results/for_tiles_1206/run_on_device.sh
# (The setup, inline when the call ran, is now bench/cpu/device_host_ab_setup.sh: same steps.)
OLD_TARGETS="--target horizon" source bench/cpu/device_host_ab_setup.sh
for round in 1 2 3; do for tree in new old; do
  for run in "lattice 1.5 1" "shuffled 1.5 1" "lattice 3.015 1" "lattice 1.5 16" "lattice 3.015 16"; do
    echo "== $tree round $round X $run"; /tmp/pb_$tree $run 3 | grep -E "count0|count1| fill"
  done
  for env in UNSORTED HALF; do echo "== $tree round $round $env lattice 1.5 1"; env $env=1 /tmp/pb_$tree lattice 1.5 1 3 | grep -E "count0|count1| fill"; done
done; done > $OUT/phases_host16.txt 2>&1
tail -3 $OUT/phases_host16.txt
