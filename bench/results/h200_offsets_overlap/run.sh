#!/usr/bin/env bash
# One call on nvidia-h200: the host->host path with the offsets copied back while the fill runs
# (new) and before it (old, HORIZON_AB_OFFSETS_FIRST=1, a switch of the measured build only),
# alternating; then the GPU suite with the GPU required.
# Usage: bash bench/results/h200_offsets_overlap/run.sh  (with .deps carried; writes under $OUT)
source bench/gpu/device_build.sh
for round in 1 2; do
  for version in new old; do
    if [ "$version" = old ]; then export HORIZON_AB_OFFSETS_FIRST=1; else unset HORIZON_AB_OFFSETS_FIRST; fi
    "$BUILD/bin/horizon_gpu_bench" --sizes 200,400 --cloud-points 0 --reps 5 --cpu-max-n 0 \
      > "$OUT/${version}_$round.csv" 2> "$OUT/${version}_$round.err"
    echo "$version $round"; cut -d, -f1,4,15,17-22 "$OUT/${version}_$round.csv" | tail -n +3
  done
done
unset HORIZON_AB_OFFSETS_FIRST
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"
