#!/usr/bin/env bash
# On the GPU machine: every test with the GPU required (ctest, the Python suite with PyTorch's
# GPU arrays, the examples and the docs' snippets), then optionally compute-sanitizer over the
# GPU tests while the host's other cores run sharded differential problems.
# Usage: [SANITIZERS="memcheck initcheck racecheck"] [FILTER='*Cuda*:*cuda*'] [SHARDS=0] [PER_SHARD=500]
#        [PARALLEL=14] [LIMIT_S=420] [DIFFERENTIAL_DEVICES=0] bash bench/device/test.sh   (writes under $OUT)
export CMAKE_ARGS="-DPython_EXECUTABLE=$(command -v python3) -Dpybind11_DIR=$(python3 -m pybind11 --cmakedir 2>/dev/null) ${CMAKE_ARGS:-}"
source bench/device/build.sh
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader | tee "$OUT/gpu.txt"
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 8 --output-on-failure -E "pip_install|find_package" > "$OUT/ctest.log" 2>&1)
grep -E "tests passed|tests failed|\(Failed\)|\(SEGFAULT\)|Skipped|\*\*\*Not Run" "$OUT/ctest.log" | tail -20
filter=${FILTER:-*Cuda*:*cuda*:PartitionedSearch.SeveralDevicesThroughSearchOptions}
shards=${SHARDS:-0} per=${PER_SHARD:-500} parallel=${PARALLEL:-14} limit=${LIMIT_S:-420}
export BUILD OUT per DIFFERENTIAL_DEVICES=${DIFFERENTIAL_DEVICES-}  # empty: the CPU backends only
seq 1 "$shards" | timeout "$limit" xargs -r -P "$parallel" -I{} sh -c '
  log=$OUT/differential_seed{}.log
  CUDA_VISIBLE_DEVICES=$DIFFERENTIAL_DEVICES OMP_NUM_THREADS=1 HORIZON_DIFFERENTIAL_SEED={} HORIZON_DIFFERENTIAL_PROBLEMS=$per \
    "$BUILD/bin/horizon_tests" --gtest_filter=Differential.* > "$log" 2>&1
  if grep -q "^\[  PASSED  \] 1 test" "$log"; then echo "seed {}: passed"; rm "$log"; else echo "seed {}: FAILED"; fi
' > "$OUT/differential_summary.txt" &
for tool in ${SANITIZERS:-}; do
  HORIZON_REQUIRE_GPU=1 timeout "$limit" compute-sanitizer --tool "$tool" --error-exitcode 99 \
    "$BUILD/bin/horizon_tests" --gtest_filter="$filter" > "$OUT/$tool.log" 2>&1 &
done
wait
for tool in ${SANITIZERS:-}; do
  echo "$tool ($filter): $(grep -E '^\[  (PASSED|FAILED)' "$OUT/$tool.log" | tr '\n' ' ') $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' "$OUT/$tool.log" | tail -1)"
done | tee "$OUT/sanitizers_summary.txt"
[ "$shards" -gt 0 ] && echo "differential: $(grep -c passed "$OUT/differential_summary.txt") of $shards shards of $per problems passed"
exit 0
