#!/usr/bin/env bash
# run_on_device.sh (old tree under .deps/old-src: f30e6f2, rows placed by memcpy), then
# place_rows_bench.cpp on all host cores with the parts alternating every row, every 25 rows
# and every 200 rows. Usage (device, .deps carried):
#   SIZES=400 REPS=2 TESTS='Partitioned*' bash bench/results/gpu_parts_on_device_1205/run_streamed_place.sh
here=bench/results/gpu_parts_on_device_1205
source $here/run_on_device.sh
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc -Ibuild-gpu/include -I/opt/deps/usr/include $here/place_rows_bench.cpp \
  build-gpu/src/libhorizon.a -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -L/usr/local/cuda/lib64 -lcudart -o place_rows_bench
for run in 1 25 200; do echo "RUN=$run"; RUN=$run ./place_rows_bench; done 2>&1 | tee $OUT/place_rows_host.txt
