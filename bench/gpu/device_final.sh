#!/usr/bin/env bash
# One call on the GPU machine for a code version's GPU figures: build, the GPU suite with the
# GPU required, horizon_gpu_bench (device-resident and host->host, against the naive kernel),
# then compute-sanitizer memcheck, racecheck and initcheck over the fill paths' tests.
# Usage: bash bench/gpu/device_final.sh  (writes under $OUT)
source bench/gpu/device_build.sh
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"
"$BUILD/bin/horizon_gpu_bench" --sizes 100,200,400 --cloud-points 8000000 --reps 3 2> "$OUT/gpu_bench.err" > "$OUT/gpu_bench.csv"
cut -d, -f1-12 "$OUT/gpu_bench.csv"
fills='Cuda.RowsOfEveryLengthAreSorted:Cuda.FewLongRowsAmongShortOnesAreSorted:Cuda.CellsWhoseStencilOutgrowsTheStageAreSorted:Cuda.UnsortedRowsHoldTheSameFamilies:Cuda.BatchedHostSearchEqualsSerial'
for tool in memcheck racecheck initcheck; do
  HORIZON_REQUIRE_GPU=1 timeout 60 compute-sanitizer --tool "$tool" --error-exitcode 1 \
    "$BUILD/bin/horizon_tests" --gtest_filter="$fills" > "$OUT/$tool.log" 2>&1
  echo "$tool rc=$? $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY|PASSED|FAILED' "$OUT/$tool.log" | tr '\n' ' ')"
done
