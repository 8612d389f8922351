#!/usr/bin/env bash
# One device call, CPU only: this tree and the tree before the tiles (.deps/old-src = 60df8f8)
# built on the GPU machine's 16-core host; the search's oracle tests; the fill pass alone
# (../cpu_phases_1205/phase_bench.cpp, min of the reps) and the whole search against the in-benchmark textbook
# cell list, the two trees alternating.
# Usage (device, .deps carried): bash bench/results/tiled_rows_1206/run_on_device.sh

CMAKE_ARGS="-DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ lscpu | grep -E "Model name|^CPU\(s\)|Flags" | cut -c1-300; git log --oneline -1; } > $OUT/machine.txt
(cd .deps/old-src && cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=/opt/deps/usr -DHORIZON_CUDA=off \
  -DHORIZON_PYTHON=off -DHORIZON_TESTS=OFF -DHORIZON_BENCH=ON -DHORIZON_MPI=OFF > /dev/null && cmake --build build -j16 > /dev/null) &
timeout 200 $BUILD/bin/horizon_tests --gtest_filter='SimdTargets.*:*Search*:Grid.*:Oracle*:CellIndex.*' > $OUT/tests.txt 2>&1
grep -E "^\[  (PASSED|FAILED) |FAILED  \]" $OUT/tests.txt | head -20
wait
I="-I/opt/deps/usr/include"; L="-L/opt/deps/usr/lib/x86_64-linux-gnu"
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc $I bench/results/cpu_phases_1205/phase_bench.cpp $BUILD/src/libhorizon.a $L -lhwy -o /tmp/pb_new
g++ -O2 -std=c++20 -fopenmp -I.deps/old-src/include -I.deps/old-src/src $I bench/results/cpu_phases_1205/phase_bench.cpp .deps/old-src/build/src/libhorizon.a $L -lhwy -o /tmp/pb_old
for round in 1; do for tree in new old; do
  for m in 1.5 3.015; do for t in 1 16; do
    echo "$tree round $round"; /tmp/pb_$tree lattice $m $t 5; UNSORTED=1 /tmp/pb_$tree lattice $m $t 5 | grep -E " fill"
    /tmp/pb_$tree random $m $t 3 | grep -E " fill"
  done; done
done; done > $OUT/phases_host16.txt 2>&1
tail -5 $OUT/phases_host16.txt
for round in 1 2; do
  timeout 100 $BUILD/bin/horizon_bench --sizes 100 --reps 3 --cloud-points 1000000 > $OUT/bench_new_$round.csv 2>&1
  timeout 100 .deps/old-src/build/bin/horizon_bench --sizes 100 --reps 3 --cloud-points 1000000 > $OUT/bench_old_$round.csv 2>&1
done
grep -E "^lattice,.*(serial|openmp),sorted" $OUT/bench_*.csv
