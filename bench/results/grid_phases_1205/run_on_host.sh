#!/usr/bin/env bash
# One device call: builds horizon_bench and grid_phases.cpp (no CUDA) on the host, runs the
# README's CPU table command, then the grid's phases at 1 and 16 threads.
# Usage (device): bash bench/results/grid_phases_1205/run_on_host.sh   (writes under $OUT)
set -u
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
cmake -S . -B build-gp -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF \
  -DCMAKE_PREFIX_PATH=/opt/deps/usr > $OUT/configure.log 2>&1
cmake --build build-gp -j 16 --target horizon horizon_bench 2>&1 | grep -E "error"
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc -I/opt/deps/usr/include bench/results/grid_phases_1205/grid_phases.cpp \
  build-gp/src/libhorizon.a -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -o build-gp/grid_phases || exit 1
lscpu > $OUT/lscpu.txt
git log --oneline -1 > $OUT/commit.txt 2>/dev/null
./build-gp/bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/cpu_host16.csv 2>&1
for problem in lattice random; do for t in 1 16; do ./build-gp/grid_phases $problem 1.5 $t 9; done; done 2>&1 | tee $OUT/grid_phases.txt
