#!/usr/bin/env bash
# One device call (CPU only): this tree and the one under .deps/old-src built without CUDA;
# cell_index_bench.cpp against each at 1-16 threads, alternating; then the README table's
# command with each (skipped with README_COMMAND=0).
# Usage (device): bash bench/results/cell_sort_parts_1205/run_on_host.sh
set -u
here=bench/results/cell_sort_parts_1205
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
for tree in . .deps/old-src; do
  cmake -S $tree -B $tree/build-ab -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF \
    -DCMAKE_PREFIX_PATH=/opt/deps/usr > $OUT/configure_$(basename $tree).log 2>&1
  cmake --build $tree/build-ab -j 16 --target horizon $([ "${README_COMMAND:-1}" = 0 ] || echo horizon_bench) 2>&1 | grep -E "error"
  g++ -O2 -std=c++20 -fopenmp -I$tree/include -I$tree/src -I/opt/deps/usr/include $here/cell_index_bench.cpp \
    $tree/build-ab/src/libhorizon.a -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -o $tree/build-ab/cell_index_bench
done
lscpu > $OUT/lscpu.txt
for round in 1 2; do for problem in lattice random; do for t in 1 2 4 8 16; do
  echo "new $(./build-ab/cell_index_bench $problem $t)"; echo "old $(.deps/old-src/build-ab/cell_index_bench $problem $t)"
done; done; done 2>&1 | tee $OUT/cell_index.txt
[ "${README_COMMAND:-1}" = 0 ] && exit 0
./build-ab/bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/new.csv 2>&1
.deps/old-src/build-ab/bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/old.csv 2>&1
