#!/usr/bin/env bash
# One call on nvidia-h200: the host->host path with the coordinates checked on the GPU (the host
# no longer reads them before the upload) and copies in 16 MB steps, against switches of the
# measured build only: HORIZON_AB_HOST_FINITE=1 (checked on the host, as before) and
# HORIZON_AB_CHUNK_MB (the copies' step; 64 before). Alternating, then the GPU suite.
# Usage: bash bench/results/h200_upload_check_chunks/run.sh  (with .deps carried; writes under $OUT)
source bench/gpu/device_build.sh
run() {  # name, env...
  local name=$1; shift
  env "$@" "$BUILD/bin/horizon_gpu_bench" --sizes 200,400 --cloud-points 0 --reps 5 --cpu-max-n 0 \
    > "$OUT/$name.csv" 2> "$OUT/$name.err"
  echo "$name"; cut -d, -f1,4,15,17-22 "$OUT/$name.csv" | tail -n +3
}
for round in 1 2; do
  run "gpu_check_chunk16_$round"
  run "gpu_check_chunk32_$round" HORIZON_AB_CHUNK_MB=32
  run "gpu_check_chunk64_$round" HORIZON_AB_CHUNK_MB=64
  run "host_check_chunk64_$round" HORIZON_AB_CHUNK_MB=64 HORIZON_AB_HOST_FINITE=1
done
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda|Validate" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"
