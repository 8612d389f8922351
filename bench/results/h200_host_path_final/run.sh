#!/usr/bin/env bash
# One call on nvidia-h200 of the final code: the host->host timings, the GPU suite with the GPU
# required, and compute-sanitizer memcheck over the host path's tests.
# Usage: bash bench/results/h200_host_path_final/run.sh  (with .deps carried; writes under $OUT)
source bench/gpu/device_build.sh
"$BUILD/bin/horizon_gpu_bench" --sizes 200,400 --cloud-points 0 --reps 5 --cpu-max-n 0 > "$OUT/gpu_bench.csv" 2> "$OUT/gpu_bench.err"
cut -d, -f1,4,15,17-22 "$OUT/gpu_bench.csv"
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda|Validate" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"
HORIZON_REQUIRE_GPU=1 timeout 150 compute-sanitizer --tool memcheck --error-exitcode 1 "$BUILD/bin/horizon_tests" \
  --gtest_filter='Cuda.NamesTheFirstNonFinitePoint:Cuda.BatchedHostSearchEqualsSerial:Cuda.RowsOfEveryLengthAreSorted' > "$OUT/memcheck.log" 2>&1
echo "memcheck rc=$? $(grep -E 'ERROR SUMMARY|PASSED|FAILED' "$OUT/memcheck.log" | tr '\n' ' ')"
