#!/usr/bin/env bash
# On the GPU machine: build, run the GPU tests (GPU required), then horizon_gpu_bench.
# Usage: [SIZES=100,400] [CLOUD=8000000] [TESTS=1] [SANITIZE='Cuda.A:Cuda.B'] [CPU_BENCH=1]
#        bash bench/gpu/device_bench.sh  (writes under $OUT)
# SANITIZE runs compute-sanitizer memcheck and racecheck over those tests; CPU_BENCH runs
# horizon_bench (CPU, all cores, against the textbook list) from the same build afterwards.
source bench/gpu/device_build.sh
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.sm,clocks.max.sm --format=csv,noheader | tee "$OUT/gpu.txt"
if [ "${TESTS:-1}" = 1 ]; then
  (cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 4 --output-on-failure -R "cuda|Cuda") > "$OUT/ctest.log" 2>&1
  grep -E "tests passed|tests failed|Failed|\*\*\*" "$OUT/ctest.log" | tail -15
fi
if [ -n "${SANITIZE:-}" ]; then
  for tool in memcheck racecheck; do
    HORIZON_REQUIRE_GPU=1 compute-sanitizer --tool "$tool" --error-exitcode 1 \
      "$BUILD/bin/horizon_tests" --gtest_filter="$SANITIZE" > "$OUT/$tool.log" 2>&1
    echo "$tool rc=$? $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY|PASSED|FAILED' "$OUT/$tool.log" | tr '\n' ' ')"
  done
fi
"$BUILD/bin/horizon_gpu_bench" --sizes "${SIZES:-100,400}" --cloud-points "${CLOUD:-8000000}" --reps 3 \
  ${BENCH_ARGS:-} 2> "$OUT/gpu_bench.err" | tee "$OUT/gpu_bench.csv"
if [ "${CPU_BENCH:-0}" = 1 ]; then
  lscpu | grep -E "Model name|^CPU\(s\)"
  "$BUILD/bin/horizon_bench" --sizes 100 --reps 3 --shuffled --cloud-points 1000000 | tee "$OUT/cpu_bench.csv"
fi
