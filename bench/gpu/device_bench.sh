#!/usr/bin/env bash
# On the GPU machine: build, run the GPU tests (GPU required), then horizon_gpu_bench.
# Usage: [SIZES=100,400] [CLOUD=8000000] [TESTS=1] bash bench/gpu/device_bench.sh  (writes under $OUT)
source bench/gpu/device_build.sh
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.sm,clocks.max.sm --format=csv,noheader | tee "$OUT/gpu.txt"
if [ "${TESTS:-1}" = 1 ]; then
  (cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 4 --output-on-failure -R "cuda|Cuda") > "$OUT/ctest.log" 2>&1
  grep -E "tests passed|tests failed|Failed|\*\*\*" "$OUT/ctest.log" | tail -15
fi
"$BUILD/bin/horizon_gpu_bench" --sizes "${SIZES:-100,400}" --cloud-points "${CLOUD:-8000000}" --reps 3 \
  ${BENCH_ARGS:-} 2> "$OUT/gpu_bench.err" | tee "$OUT/gpu_bench.csv"
