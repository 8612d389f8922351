#!/usr/bin/env bash
# One device call, CPU only: this tree (the fill's rows wait in a ring of up to 64 buffers and
# are placed together) and .deps/old-src (= 29676a5, one tile's rows at a time) built on the GPU
# machine's 16-core host; the search's oracle tests; the fill pass alone
# (../cpu_phases_1205/phase_bench.cpp, min of the reps) and the whole search against the
# in-benchmark textbook list, trees alternating.
# Usage (device, .deps carried): bash bench/results/row_ring_1206/run_on_device.sh
# (The setup, inline when the call ran, is now bench/cpu/device_host_ab_setup.sh: same steps.)
source bench/cpu/device_host_ab_setup.sh
for round in 1 2; do for tree in new old; do
  for m in 1.5 3.015; do for t in 1 16; do for w in lattice shuffled random; do
    echo "== $tree round $round $w m=$m threads=$t"; /tmp/pb_$tree $w $m $t 3 | grep -E " fill"
  done; done; done
  for w in lattice shuffled; do echo "== $tree round $round UNSORTED $w m=1.5 threads=1"; UNSORTED=1 /tmp/pb_$tree $w 1.5 1 3 | grep -E " fill"; done
done; done > $OUT/phases_host16.txt 2>&1
for round in 1 2; do for tree in new old; do
  bin=$BUILD/bin; [ $tree = old ] && bin=$OLD_BIN
  timeout 100 $bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/host16_bench_${tree}_$round.csv 2>&1
done; done
grep -E "^(lattice|lattice-shuffled|random).*(serial|openmp),sorted" $OUT/host16_bench_*.csv | cut -c1-200
