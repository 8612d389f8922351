#!/usr/bin/env bash
# The device Verlet list on the GPU machine: build, the GPU tests, memcheck and racecheck of its
# kernels, and horizon_device_verlet_bench. Usage: bash bench/gpu/device_verlet.sh (writes $OUT)
source bench/gpu/device_build.sh
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 8 -R "cuda|Cuda" > "$OUT/gpu_tests.txt" 2>&1)
tail -3 "$OUT/gpu_tests.txt"
"$BUILD/bin/horizon_device_verlet_bench" --sizes 100 200 > "$OUT/device_verlet_bench.csv"
cat "$OUT/device_verlet_bench.csv"
for tool in memcheck racecheck; do
  timeout 200 compute-sanitizer --tool $tool --error-exitcode 1 "$BUILD/bin/horizon_tests" \
    --gtest_filter='Cuda.DeviceVerlet*' > "$OUT/$tool.txt" 2>&1
  echo "$tool exit $?"; tail -2 "$OUT/$tool.txt"
done
