#!/usr/bin/env bash
# Second device call, CPU only, with the final ring (32 KB): the README's host CPU table
# (horizon_bench once, portable build), then the fill pass alone against .deps/old-src
# (= 29676a5) where the first call (a 256 KB ring) looked slower or faster, three rounds alternating.
# Usage (device, .deps carried): bash bench/results/row_ring_1206/final_on_device.sh
CMAKE_ARGS="-DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ lscpu | grep -E "Model name|^CPU\(s\)|Flags" | cut -c1-300; nvidia-smi -L; } > $OUT/machine.txt
(cd .deps/old-src && cmake -S . -B build-host -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=/opt/deps/usr -DHORIZON_CUDA=off \
  -DHORIZON_PYTHON=off -DHORIZON_TESTS=OFF -DHORIZON_BENCH=ON -DHORIZON_MPI=OFF > /dev/null && cmake --build build-host -j16 > /dev/null) &
timeout 200 $BUILD/bin/horizon_tests --gtest_filter='SimdTargets.*:*Search*:Grid.*:Oracle*:CellIndex.*:*Half*:*Unsorted*:*Radii*' > $OUT/tests.txt 2>&1
grep -E "^\[  (PASSED|FAILED) |FAILED  \]" $OUT/tests.txt | head -20
wait
timeout 120 $BUILD/bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/host16_bench_final.csv 2>&1
I="-I/opt/deps/usr/include"; L="-L/opt/deps/usr/lib/x86_64-linux-gnu"
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc $I bench/results/cpu_phases_1205/phase_bench.cpp $BUILD/src/libhorizon.a $L -lhwy -o /tmp/pb_new
g++ -O2 -std=c++20 -fopenmp -I.deps/old-src/include -I.deps/old-src/src $I bench/results/cpu_phases_1205/phase_bench.cpp .deps/old-src/build-host/src/libhorizon.a $L -lhwy -o /tmp/pb_old
for round in 1 2 3; do for tree in new old; do
  for run in "lattice 3.015 16" "lattice 3.015 1" "shuffled 1.5 1" "random 1.5 16" "lattice 1.5 16"; do
    echo "== $tree round $round $run"; /tmp/pb_$tree $run 3 | grep -E " fill"
  done
done; done > $OUT/phases_host16.txt 2>&1
grep -E "^(lattice|lattice-shuffled|random),.*(serial|openmp),sorted" $OUT/host16_bench_final.csv | cut -c1-200
