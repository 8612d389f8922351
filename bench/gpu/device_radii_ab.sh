#!/usr/bin/env bash
# Per-point radii A/B on the GPU machine's host CPU: builds this tree and an older one (unpacked
# under .deps/old-src) without CUDA, runs the CPU radii and SIMD-target tests on this one, then
# horizon_radii_bench of both, interleaved. Usage: bash bench/gpu/device_radii_ab.sh (writes under $OUT)
set -u
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
for tree in . .deps/old-src; do
  cmake -S $tree -B $tree/build-ab -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off \
    -DHORIZON_MPI=OFF -DCMAKE_PREFIX_PATH=/opt/deps/usr > $OUT/configure_$(basename $tree).log 2>&1
  cmake --build $tree/build-ab -j "$(nproc)" --target horizon_radii_bench horizon_tests 2>&1 | grep -E "error"
done
lscpu > $OUT/lscpu.txt
./build-ab/bin/horizon_tests --gtest_filter='SimdTargets*:*RadiiTest*serial*:*RadiiTest*openmp*:RadiiThreads*' > $OUT/cpu_tests.txt 2>&1
tail -3 $OUT/cpu_tests.txt
for round in $(seq ${ROUNDS:-2}); do
  ./build-ab/bin/horizon_radii_bench --points 1000000 --reps 3 --rules ${RULES:-gather} > $OUT/new_$round.csv 2>&1
  .deps/old-src/build-ab/bin/horizon_radii_bench --points 1000000 --reps 3 --rules ${RULES:-gather} > $OUT/old_$round.csv 2>&1
done
./build-ab/bin/horizon_radii_bench --points 1000000 --reps 3 > $OUT/new_all_rules.csv 2>&1
for f in $OUT/*.csv; do echo "== $f"; cat $f; done
