#!/usr/bin/env bash
# Builds libhorizon (no CUDA) and phase_bench.cpp on the device machine's host, then times the
# search's phases at 1, 8 and 16 threads. Usage (device): bash bench/results/cpu_phases_1205/run_on_host.sh
set -u
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
cmake -S . -B build-ph -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF \
  -DCMAKE_PREFIX_PATH=/opt/deps/usr > $OUT/configure.log 2>&1
cmake --build build-ph -j 16 --target horizon 2>&1 | grep -E "error"
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc -I/opt/deps/usr/include bench/results/cpu_phases_1205/phase_bench.cpp \
  build-ph/src/libhorizon.a -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -o build-ph/phase_bench || exit 1
for problem in lattice random; do for m in 1.5 3.015; do for t in 1 8 16; do
  ./build-ph/phase_bench $problem $m $t ${REPS:-5}
done; done; done 2>&1 | tee $OUT/phases.txt
for m in 1.5 3.015; do for t in 1 16; do echo "unsorted rows:"; UNSORTED=1 ./build-ph/phase_bench lattice $m $t ${REPS:-5}; done; done 2>&1 | tee -a $OUT/phases.txt
