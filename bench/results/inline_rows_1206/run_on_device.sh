#!/usr/bin/env bash
# One device call, CPU only: this tree (b809c36: count and fills in tiles, dense rows of cells
# inline) against .deps/old-src (= d073cc5, before the inline rows) on the GPU machine's 16-core
# host: the search's oracle tests, then horizon_bench (the README's command) alternating, 2 rounds.
# Usage (device, .deps carried): bash bench/results/inline_rows_1206/run_on_device.sh
CMAKE_ARGS="-DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ lscpu | grep -E "Model name|^CPU\(s\)" ; nvidia-smi -L; } > $OUT/machine.txt
(cd .deps/old-src && cmake -S . -B build-host -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=/opt/deps/usr -DHORIZON_CUDA=off \
  -DHORIZON_PYTHON=off -DHORIZON_TESTS=OFF -DHORIZON_BENCH=ON -DHORIZON_MPI=OFF > /dev/null && cmake --build build-host -j16 --target horizon_bench > /dev/null) &
timeout 200 $BUILD/bin/horizon_tests --gtest_filter='SimdTargets.*:*Search*:Grid.*:Oracle*:CellIndex.*' > $OUT/tests.txt 2>&1
grep -E "^\[  (PASSED|FAILED) |FAILED  \]" $OUT/tests.txt | head -20
wait
for round in 1 2; do for tree in new old; do
  bin=$BUILD/bin; [ $tree = old ] && bin=.deps/old-src/build-host/bin
  timeout 120 $bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/host16_${tree}_$round.csv 2>&1
done; done
grep -E "^(lattice|random),.*(serial|openmp),sorted" $OUT/host16_*.csv | cut -d, -f1,4,6,9,13,16
