#!/usr/bin/env bash
# CPU A/B on the GPU machine's host: builds this tree and an older one (unpacked under
# .deps/old-src) without CUDA, runs the CPU oracle tests on this one, then a benchmark of
# both, interleaved, in one call. Usage: bash bench/gpu/device_cpu_ab.sh  (writes under $OUT)
# BENCH picks the benchmark, ARGS its arguments, TESTS the gtest filter; e.g. per-point radii:
#   BENCH=horizon_radii_bench ARGS="--points 1000000 --reps 3 --rules gather" \
#   TESTS='SimdTargets*:*RadiiTest*serial*:*RadiiTest*openmp*:RadiiThreads*' bash bench/gpu/device_cpu_ab.sh
set -u
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
BENCH=${BENCH:-horizon_bench}
ARGS=${ARGS:---sizes 100 --reps 3 --shuffled --cloud-points 1000000}
TESTS=${TESTS:-CellIndex*:RadixSort*:Buffer*:SimdTargets*:AllBackends/OracleTest.*/serial*:AllBackends/OracleTest.*/openmp*:Differential*:Backends*}
for tree in . .deps/old-src; do
  cmake -S $tree -B $tree/build-ab -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off \
    -DHORIZON_MPI=OFF -DCMAKE_PREFIX_PATH=/opt/deps/usr > $OUT/configure_$(basename $tree).log 2>&1
  cmake --build $tree/build-ab -j "$(nproc)" --target $BENCH horizon_tests 2>&1 | grep -E "error" 
done
lscpu > $OUT/lscpu.txt
./build-ab/bin/horizon_tests --gtest_filter="$TESTS" > $OUT/cpu_tests.txt 2>&1
tail -3 $OUT/cpu_tests.txt
for round in $(seq ${ROUNDS:-1}); do
  ./build-ab/bin/$BENCH $ARGS > $OUT/new_$round.csv 2>&1
  .deps/old-src/build-ab/bin/$BENCH $ARGS > $OUT/old_$round.csv 2>&1
done
