#!/usr/bin/env bash
# One device call, CPU only: the fill's tiles dispatched by ForTiles<tile> (this tree) against
# .deps/old-src (= 435c7d3, its own 4/2/1 dispatch), built on the GPU machine's 16-core host;
# the search's oracle tests; the count and fill passes alone (../cpu_phases_1205/phase_bench.cpp,
# min of 3 reps), trees alternating, three rounds.
# Usage (device, .deps carried): bash bench/results/for_tiles_1206/run_on_device.sh
CMAKE_ARGS="-DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ lscpu | grep -E "Model name|^CPU\(s\)" | cut -c1-300; nvidia-smi -L; } > $OUT/machine.txt
(cd .deps/old-src && cmake -S . -B build-host -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=/opt/deps/usr -DHORIZON_CUDA=off \
  -DHORIZON_PYTHON=off -DHORIZON_TESTS=OFF -DHORIZON_BENCH=ON -DHORIZON_MPI=OFF > /dev/null && cmake --build build-host -j16 --target horizon > /dev/null) &
timeout 200 $BUILD/bin/horizon_tests --gtest_filter='SimdTargets.*:*Search*:Grid.*:Oracle*:CellIndex.*:*Half*:*Unsorted*:*Radii*' > $OUT/tests.txt 2>&1
grep -E "^\[  (PASSED|FAILED) |FAILED  \]" $OUT/tests.txt | head -20
wait
I="-I/opt/deps/usr/include"; L="-L/opt/deps/usr/lib/x86_64-linux-gnu"
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc $I bench/results/cpu_phases_1205/phase_bench.cpp $BUILD/src/libhorizon.a $L -lhwy -o /tmp/pb_new
g++ -O2 -std=c++20 -fopenmp -I.deps/old-src/include -I.deps/old-src/src $I bench/results/cpu_phases_1205/phase_bench.cpp .deps/old-src/build-host/src/libhorizon.a $L -lhwy -o /tmp/pb_old
for round in 1 2 3; do for tree in new old; do
  for run in "lattice 1.5 1" "shuffled 1.5 1" "lattice 3.015 1" "lattice 1.5 16" "lattice 3.015 16"; do
    echo "== $tree round $round X $run"; /tmp/pb_$tree $run 3 | grep -E "count0|count1| fill"
  done
  for env in UNSORTED HALF; do echo "== $tree round $round $env lattice 1.5 1"; env $env=1 /tmp/pb_$tree lattice 1.5 1 3 | grep -E "count0|count1| fill"; done
done; done > $OUT/phases_host16.txt 2>&1
tail -3 $OUT/phases_host16.txt
