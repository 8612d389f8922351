#!/usr/bin/env bash
# One call on the GPU machine: the per-cell count pass (cell_count.cuh) against the
# thread-per-point one (HORIZON_COUNT_PER_THREAD=1): the GPU suite (both), horizon_gpu_bench
# (the per-cell count with host->host and openmp, the other device-resident only), Nsight Compute kernel durations and instructions of lattice n = 200
# (both), horizon_periodic_bench, then compute-sanitizer memcheck and racecheck over the per-cell paths' tests.
# Usage: bash bench/gpu/device_count_ab.sh  (writes under $OUT)
source bench/gpu/device_build.sh
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"; grep -E "\(Failed\)|Exception" "$OUT/gpu_tests.txt" | head -20
HORIZON_REQUIRE_GPU=1 HORIZON_COUNT_PER_THREAD=1 "$BUILD/bin/horizon_tests" --gtest_filter='Cuda.*' 2>&1 | tail -3
bench() { "$BUILD/bin/horizon_gpu_bench" --sizes 100,200,400 --cloud-points 8000000 --reps 3 "$@" 2>>"$OUT/bench.err"; }
bench > "$OUT/bench_cells.csv"; HORIZON_COUNT_PER_THREAD=1 bench --no-host > "$OUT/bench_thread.csv"
for f in "$OUT"/bench_cells.csv "$OUT"/bench_thread.csv; do echo "== $f"; cut -d, -f1-12 "$f" | tail -n +2; done
profile() {
  ncu --clock-control none --metrics gpu__time_duration.sum,smsp__inst_executed.sum --csv \
    "$BUILD/bin/horizon_gpu_bench" --sizes 200 --cloud-points 0 --reps 1 --no-host 2>/dev/null |
  python3 -c '
import csv, sys
rows = [r for r in csv.reader(l for l in sys.stdin if l.startswith("\""))][1:]
for r in rows:
    if any(k in r[4] for k in ("count_", "fill_", "cell_families", "stencil_words", "families<")):
        print(f"{r[0]:>4} {r[-3][:28]:28} {r[-1]:>16}  {r[4][:80]}")'
}
{ echo "# per-cell count"; profile; echo "# thread-per-point count"; HORIZON_COUNT_PER_THREAD=1 profile; } > "$OUT/ncu.txt"
cat "$OUT/ncu.txt"
"$BUILD/bin/horizon_periodic_bench" --reps 5 > "$OUT/periodic.csv" 2>&1; cat "$OUT/periodic.csv"
fills='Cuda.RowsOfEveryLengthAreSorted:Cuda.CellsWhoseStencilOutgrowsTheStageAreSorted:Cuda.FillsWithoutHitBitsWithinAGpuMemoryLimit'
for tool in memcheck racecheck; do
  HORIZON_REQUIRE_GPU=1 timeout 50 compute-sanitizer --tool "$tool" --error-exitcode 1 \
    "$BUILD/bin/horizon_tests" --gtest_filter="$fills" > "$OUT/$tool.log" 2>&1
  echo "$tool rc=$? $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY|PASSED|FAILED|OK \]' "$OUT/$tool.log" | tr '\n' ' ')"
done
