#!/usr/bin/env bash
# Verlet A/B on the GPU machine: builds this tree and an older one (unpacked under .deps/old-src),
# runs the GPU suite (GPU required) and compute-sanitizer on the device Verlet list of this one,
# then horizon_device_verlet_bench and the 16-core host's horizon_verlet_bench of both, alternately.
# Usage (repository root, old tree in .deps/old-src, carry [".deps"]):
#   [ROUNDS=2] [SANITIZERS="memcheck racecheck initcheck"] [CPU_BENCH=0] bash bench/gpu/device_verlet_ab.sh
# (writes under $OUT; CPU_BENCH=0 leaves out the host's horizon_verlet_bench)
source bench/gpu/device_build.sh
source bench/gpu/device_build_old.sh horizon_device_verlet_bench horizon_verlet_bench
(cd build-gpu && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda|Verlet|SimdTargets" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"; grep -E "\(Failed\)" "$OUT/gpu_tests.txt" | head
for tool in ${SANITIZERS:-}; do
  timeout 100 compute-sanitizer --tool $tool --error-exitcode 1 build-gpu/bin/horizon_tests \
    --gtest_filter='Cuda.DeviceVerlet*' > "$OUT/$tool.txt" 2>&1
  echo "$tool exit $?"; tail -1 "$OUT/$tool.txt"
done
for round in $(seq ${ROUNDS:-2}); do
  for tree in new old; do
    bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
    $bin/horizon_device_verlet_bench --sizes 100 200 > $OUT/device_${tree}_$round.csv
    [ "${CPU_BENCH:-1}" = 0 ] || $bin/horizon_verlet_bench --reps 5 > $OUT/cpu_${tree}_$round.csv
  done
done
head -100 $OUT/device_*.csv $OUT/cpu_*.csv 2>/dev/null
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"
for tool in ${SANITIZERS:-}; do echo "$tool: $(tail -1 "$OUT/$tool.txt")"; done
