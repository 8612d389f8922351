#!/usr/bin/env bash
# On the GPU machine (issue 13): compute-sanitizer memcheck, initcheck and racecheck over the GPU
# tests of horizon_tests (required to run: HORIZON_REQUIRE_GPU=1), while the host's other cores
# run SHARDS x PER_SHARD differential problems (seeds 1..SHARDS) on the CPU backends and in
# batches. Usage: bash bench/gpu/device_hardening.sh   (logs under $OUT)
source bench/gpu/device_build.sh
shards=${SHARDS:-12} per=${PER_SHARD:-8334} limit=${LIMIT_S:-330}
for s in $(seq 1 "$shards"); do
  CUDA_VISIBLE_DEVICES= OMP_NUM_THREADS=1 HORIZON_DIFFERENTIAL_SEED=$s HORIZON_DIFFERENTIAL_PROBLEMS=$per \
    timeout "$limit" "$BUILD/bin/horizon_tests" --gtest_filter='Differential.*' > "$OUT/differential_seed$s.log" 2>&1 &
done
for tool in memcheck initcheck racecheck; do
  HORIZON_REQUIRE_GPU=1 timeout "$limit" compute-sanitizer --tool $tool --error-exitcode 99 \
    "$BUILD/bin/horizon_tests" --gtest_filter='*Cuda*:*cuda*:PartitionedSearch.SeveralDevicesThroughSearchOptions' > "$OUT/$tool.log" 2>&1 &
done
wait
for tool in memcheck initcheck racecheck; do
  echo "$tool: $(grep -E '^\[==========\]|^\[  (PASSED|FAILED)' "$OUT/$tool.log" | tr '\n' ' ') $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' "$OUT/$tool.log" | tail -1)"
done | tee "$OUT/sanitizers_summary.txt"
for s in $(seq 1 "$shards"); do
  echo "seed $s: $(grep -E '^\[  (PASSED|FAILED)|Failure|problem [0-9]+ of seed' "$OUT/differential_seed$s.log" | head -3 | tr '\n' ' ')"
done | tee "$OUT/differential_summary.txt"
