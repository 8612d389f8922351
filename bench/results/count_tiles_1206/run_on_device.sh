#!/usr/bin/env bash
# One device call, CPU only: this tree (the count pass in tiles; unsorted and half fills in tiles)
# and .deps/old-src (= 736603a, before both) built on the GPU machine's 16-core host; the
# search's oracle tests; the count and fill passes alone (../cpu_phases_1205/phase_bench.cpp, min
# of the reps) and the whole search against the in-benchmark textbook list, trees alternating.
# Usage (device, .deps carried): bash bench/results/count_tiles_1206/run_on_device.sh
# (The setup, inline when the call ran, is now bench/cpu/device_host_ab_setup.sh: same steps.)
TEST_FILTER='SimdTargets.*:*Search*:Grid.*:Oracle*:CellIndex.*:*Half*:*Unsorted*' source bench/cpu/device_host_ab_setup.sh
for round in 1 2; do for tree in new old; do
  for m in 1.5 3.015; do for t in 1 16; do
    for env in X=1 UNSORTED=1 HALF=1; do echo "== $tree round $round $env lattice m=$m threads=$t"; env $env /tmp/pb_$tree lattice $m $t 3 | grep -E "count0|count1| fill"; done
  done; done
done; done > $OUT/phases_host16.txt 2>&1
for round in 1 2; do for tree in new old; do
  bin=$BUILD/bin; [ $tree = old ] && bin=$OLD_BIN
  timeout 120 $bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/host16_bench_${tree}_$round.csv 2>&1
done; done
grep -E "^lattice,.*(serial|openmp),sorted" $OUT/host16_bench_*.csv | cut -c1-200
