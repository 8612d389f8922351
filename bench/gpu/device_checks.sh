#!/usr/bin/env bash
# One call on the GPU machine for a code version: build with CUDA, the GPU suite with the GPU
# required, then on the host CPU horizon_bench (the README's CPU table) and
# horizon_periodic_bench, the latter also of an older tree under .deps/old-src when there is
# one (built without CUDA). Usage: bash bench/gpu/device_checks.sh  (writes under $OUT)
source bench/gpu/device_build.sh
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 8 -R "cuda|Cuda" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"
lscpu > "$OUT/lscpu.txt"
"$BUILD/bin/horizon_bench" --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > "$OUT/cpu_bench.csv" 2>&1
"$BUILD/bin/horizon_periodic_bench" --reps 5 > "$OUT/periodic_new.csv"
if [ -d .deps/old-src ]; then
  cmake -S .deps/old-src -B .deps/old-src/build-ab -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off \
    -DHORIZON_MPI=OFF -DHORIZON_TESTS=OFF -DCMAKE_PREFIX_PATH=/opt/deps/usr > "$OUT/configure_old.log" 2>&1
  cmake --build .deps/old-src/build-ab -j "$(nproc)" --target horizon_periodic_bench 2>&1 | grep -E "error"
  .deps/old-src/build-ab/bin/horizon_periodic_bench --reps 5 > "$OUT/periodic_old.csv"
fi
tail -n +1 "$OUT"/periodic_*.csv
