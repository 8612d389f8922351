#!/usr/bin/env bash
# On the GPU machine: build, run every test with the GPU required, memcheck a small search.
# Writes logs under $OUT.
source bench/gpu/device_build.sh
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader | tee "$OUT/gpu.txt"
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 8 --output-on-failure) > "$OUT/ctest.log" 2>&1
grep -E "tests passed|tests failed|Failed|\*\*\*" "$OUT/ctest.log" | tail -15
compute-sanitizer --tool memcheck "$BUILD/bin/horizon" search lattice:20 --horizon 0.75 --backend cuda --half \
  > "$OUT/memcheck.log" 2>&1
compute-sanitizer --tool memcheck "$BUILD/bin/horizon" search lattice:12 --horizon 2.5 --backend cuda --metric l1 \
  --cells-per-horizon 3 >> "$OUT/memcheck.log" 2>&1
grep -E "ERROR SUMMARY|neighbours" "$OUT/memcheck.log"
