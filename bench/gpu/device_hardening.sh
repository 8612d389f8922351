#!/usr/bin/env bash
# On the GPU machine (issue 13): compute-sanitizer over the GPU tests of horizon_tests (required
# to run: HORIZON_REQUIRE_GPU=1) while the host's other cores run differential problems on the
# CPU backends (and cuda with DIFFERENTIAL_DEVICES=0) and in batches: SHARDS shards of PER_SHARD problems (seed = shard number),
# PARALLEL at a time, for at most LIMIT_S seconds. Usage:
#   TOOLS="memcheck initcheck racecheck" FILTER='*Cuda*:*cuda*' bash bench/gpu/device_hardening.sh
# Writes $OUT/sanitizers_summary.txt, $OUT/differential_summary.txt (a line per shard) and the
# logs of failed shards only.
source bench/gpu/device_build.sh
tools=${TOOLS-memcheck initcheck racecheck} filter=${FILTER:-*Cuda*:*cuda*:PartitionedSearch.SeveralDevicesThroughSearchOptions}
shards=${SHARDS:-200} per=${PER_SHARD:-500} parallel=${PARALLEL:-14} limit=${LIMIT_S:-420}
export BUILD OUT per DIFFERENTIAL_DEVICES=${DIFFERENTIAL_DEVICES-}  # empty: the CPU backends only
seq 1 "$shards" | timeout "$limit" xargs -P "$parallel" -I{} sh -c '
  log=$OUT/differential_seed{}.log
  CUDA_VISIBLE_DEVICES=$DIFFERENTIAL_DEVICES OMP_NUM_THREADS=1 HORIZON_DIFFERENTIAL_SEED={} HORIZON_DIFFERENTIAL_PROBLEMS=$per \
    "$BUILD/bin/horizon_tests" --gtest_filter=Differential.* > "$log" 2>&1
  if grep -q "^\[  PASSED  \] 1 test" "$log"; then echo "seed {}: passed: $(grep compared "$log")"; rm "$log"; else echo "seed {}: FAILED"; fi
' > "$OUT/differential_summary.txt" &
for tool in $tools; do
  HORIZON_REQUIRE_GPU=1 timeout "$limit" compute-sanitizer --tool $tool --error-exitcode 99 \
    "$BUILD/bin/horizon_tests" --gtest_filter="$filter" > "$OUT/$tool.log" 2>&1 &
done
wait
for tool in $tools; do
  [ -n "$tool" ] || continue
  echo "$tool ($filter): $(grep -E '^\[==========\] [0-9]+ tests.*ran|^\[  (PASSED|FAILED)' "$OUT/$tool.log" | tr '\n' ' ') $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' "$OUT/$tool.log" | tail -1)"
done | tee "$OUT/sanitizers_summary.txt"
echo "differential: $(grep -c passed "$OUT/differential_summary.txt") shards of $per problems passed, $(grep -c FAILED "$OUT/differential_summary.txt") failed" | tee -a "$OUT/differential_summary.txt"
