#!/usr/bin/env bash
# One call on the GPU machine for a code version's GPU figures: build, horizon_gpu_bench
# (device-resident and host->host, against the naive kernel; written as it runs, so a call cut
# short keeps what ran), the GPU suite with the GPU required, then compute-sanitizer memcheck,
# racecheck and initcheck over the fill paths' and the device Verlet list's tests.
# Usage: bash bench/gpu/device_final.sh  (writes under $OUT; SIZES, CLOUD and REPS override the bench's)
source bench/gpu/device_build.sh
"$BUILD/bin/horizon_gpu_bench" --sizes "${SIZES:-100,200,400}" --cloud-points "${CLOUD:-8000000}" --reps "${REPS:-3}" \
  2> "$OUT/gpu_bench.err" | tee "$OUT/gpu_bench.csv" | cut -d, -f1-12
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"
fills='Cuda.RowsOfEveryLengthAreSorted:Cuda.FewLongRowsAmongShortOnesAreSorted:Cuda.CellsWhoseStencilOutgrowsTheStageAreSorted:Cuda.UnsortedRowsHoldTheSameFamilies:Cuda.BatchedHostSearchEqualsSerial:Cuda.DeviceVerlet*'
for tool in memcheck racecheck initcheck; do
  HORIZON_REQUIRE_GPU=1 timeout 90 compute-sanitizer --tool "$tool" --error-exitcode 1 \
    "$BUILD/bin/horizon_tests" --gtest_filter="$fills" > "$OUT/$tool.log" 2>&1
  echo "$tool rc=$? $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY|PASSED|FAILED' "$OUT/$tool.log" | tr '\n' ' ')"
done
