#!/usr/bin/env bash
# One device call (CPU only): this tree against the one under .deps/old-src (both built without
# CUDA by bench/gpu/device_cpu_ab.sh): horizon_verlet_bench alternately, then filter_phases.cpp
# (bond filters: search, filter, the filter's move of rows, a copy of the list) of each at 1 and
# 16 threads. Usage (device, .deps carried): bash bench/results/streamed_rows_1205/run_on_host.sh
set -u
here=bench/results/streamed_rows_1205
BENCH=horizon_verlet_bench ARGS="--reps 5" ROUNDS=${ROUNDS:-2} \
  TESTS='Verlet*:*Select*:BondFilter*:BlockFilter*:*Streamed*' bash bench/gpu/device_cpu_ab.sh
for tree in . .deps/old-src; do
  g++ -O2 -std=c++20 -fopenmp -I$tree/include -I$tree/src -I/opt/deps/usr/include $here/filter_phases.cpp \
    $tree/build-ab/src/libhorizon.a -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -o $tree/build-ab/filter_phases
done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
for round in 1 2; do for t in 16 1; do
  echo "new $(./build-ab/filter_phases $t 2>/dev/null | tail -1)"
  echo "old $(.deps/old-src/build-ab/filter_phases $t 2>/dev/null | tail -1)"
done; done 2>&1 | tee $OUT/filter_phases.txt
