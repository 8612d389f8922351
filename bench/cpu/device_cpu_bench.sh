#!/usr/bin/env bash
# The CPU benchmark on the GPU machine's host (16 cores): a portable build (no -march=native, no
# CUDA), the SIMD-target oracle test, then horizon_bench against the textbook cell list.
# Needs the carried .deps/*.deb (highway, nanoflann, CLI11, GoogleTest). Writes under $OUT.
set -euo pipefail
mkdir -p /opt/deps
for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
BUILD=build-cpu
cmake -S . -B $BUILD -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_MPI=OFF \
  -DCMAKE_PREFIX_PATH=/opt/deps/usr > "$OUT/configure.log" 2>&1 || { cat "$OUT/configure.log"; exit 1; }
cmake --build $BUILD -j "$(nproc)" > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; exit 1; }
lscpu > "$OUT/lscpu.txt"
grep -E "Model name|^CPU\(s\)" "$OUT/lscpu.txt"
$BUILD/bin/horizon_tests --gtest_filter='SimdTargets*:AllBackends/OracleTest.*/serial*:AllBackends/OracleTest.*/openmp*' \
  > "$OUT/tests.log" 2>&1; tail -3 "$OUT/tests.log"
$BUILD/bin/horizon_bench --sizes 100 --reps 3 ${BENCH_ARGS:-} | tee "$OUT/cpu_bench.csv"
