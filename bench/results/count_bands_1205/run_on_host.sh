#!/usr/bin/env bash
# Builds libhorizon (no CUDA), the CPU tests and count_bench.cpp on the device machine's host,
# runs the count-pass and oracle tests at up to 16 threads, the count pass with bands against
# slabs only (same process), then horizon_bench at m = 1.5 for the 16-thread scaling.
# Usage (device): bash bench/results/count_bands_1205/run_on_host.sh   (writes under $OUT)
set -u
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
cmake -S . -B build-cb -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF \
  -DCMAKE_PREFIX_PATH=/opt/deps/usr > $OUT/configure.log 2>&1
cmake --build build-cb -j 16 --target horizon horizon_tests horizon_bench 2>&1 | grep -E "error"
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc -I/opt/deps/usr/include bench/results/count_bands_1205/count_bench.cpp \
  build-cb/src/libhorizon.a -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -o build-cb/count_bench || exit 1
lscpu > $OUT/lscpu.txt
./build-cb/bin/horizon_tests --gtest_filter='CountPassBlocks*:Backends.*:AllBackends/OracleTest.*/openmp*' > $OUT/tests.txt 2>&1
tail -3 $OUT/tests.txt
for round in 1 2; do for problem in lattice random; do for m in 1.5 3.015; do for t in 16 8; do
  ./build-cb/count_bench $problem $m $t 15
done; done; done; done 2>&1 | tee $OUT/count_bench.txt
./build-cb/bin/horizon_bench --sizes 100 --m 1.5 --reps 5 --cloud-points 1000000 > $OUT/bench_m1.5.csv 2>&1
