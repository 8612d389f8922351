#!/usr/bin/env bash
# On the GPU machine: build, run the GPU tests (GPU required), then horizon_gpu_bench with the
# per-cell build kernels (default) and, device-resident only, with the per-point kernels.
# Usage: [SIZES=100,400] [CLOUD=8000000] [TESTS=1] bash bench/gpu/device_bench.sh  (writes under $OUT)
source bench/gpu/device_build.sh
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.sm,clocks.max.sm --format=csv,noheader | tee "$OUT/gpu.txt"
if [ "${TESTS:-1}" = 1 ]; then
  (cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 4 --output-on-failure -R "cuda|Cuda") > "$OUT/ctest.log" 2>&1
  grep -E "tests passed|tests failed|Failed|\*\*\*" "$OUT/ctest.log" | tail -15
fi
"$BUILD/bin/horizon_gpu_bench" --sizes "${SIZES:-100,400}" --cloud-points "${CLOUD:-8000000}" --reps 3 \
  2> "$OUT/gpu_bench_cell.err" | tee "$OUT/gpu_bench_cell.csv"
HORIZON_CUDA_KERNELS=point "$BUILD/bin/horizon_gpu_bench" --sizes "${SIZES:-100,400}" --cloud-points "${CLOUD:-8000000}" \
  --reps 3 --no-host 2> "$OUT/gpu_bench_point.err" | tee "$OUT/gpu_bench_point.csv"
