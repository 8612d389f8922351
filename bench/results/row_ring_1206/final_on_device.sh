#!/usr/bin/env bash
# Second device call, CPU only, with the final ring (32 KB): the README's host CPU table
# (horizon_bench once, portable build), then the fill pass alone against .deps/old-src
# (= 29676a5) where the first call (a 256 KB ring) looked slower or faster, three rounds alternating.
# Usage (device, .deps carried): bash bench/results/row_ring_1206/final_on_device.sh
# (The setup, inline when the call ran, is now bench/cpu/device_host_ab_setup.sh: same steps.)
source bench/cpu/device_host_ab_setup.sh
timeout 120 $BUILD/bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/host16_bench_final.csv 2>&1
for round in 1 2 3; do for tree in new old; do
  for run in "lattice 3.015 16" "lattice 3.015 1" "shuffled 1.5 1" "random 1.5 16" "lattice 1.5 16"; do
    echo "== $tree round $round $run"; /tmp/pb_$tree $run 3 | grep -E " fill"
  done
done; done > $OUT/phases_host16.txt 2>&1
grep -E "^(lattice|lattice-shuffled|random),.*(serial|openmp),sorted" $OUT/host16_bench_final.csv | cut -c1-200
