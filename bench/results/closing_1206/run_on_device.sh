#!/usr/bin/env bash
# The code at the closing of issues 8 and 9 (CPU search as f451ca5) against the in-benchmark textbook
# list on the GPU machine's 16-core host: a portable CPU-only build of horizon_bench alone, one run.
# Usage (device, .deps carried): bash bench/results/closing_1206/run_on_device.sh
set -e
mkdir -p /opt/deps
for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
cmake -S . -B build-cpu -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_MPI=OFF -DHORIZON_PYTHON=off \
  -DHORIZON_TESTS=OFF -DCMAKE_PREFIX_PATH=/opt/deps/usr > /dev/null
cmake --build build-cpu -j "$(nproc)" --target horizon_bench > /dev/null
lscpu | grep -E "Model name|^CPU\(s\)" > $OUT/machine.txt
build-cpu/bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/host16_bench.csv
grep -E "^(lattice|lattice-shuffled|random),.*,(serial|textbook),[a-z]*,1,1," $OUT/host16_bench.csv | cut -d, -f1,4,6,7,13,16 || true
