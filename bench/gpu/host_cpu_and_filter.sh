#!/usr/bin/env bash
# The GPU machine's host, one call: this tree against .deps/old-src, processes alternating:
# horizon_bench on the lattice (serial and 16 threads), then the bond-filter ratio driver of
# bench/results/bond_filter_simd_2core_zen5/ (16 threads and 1). Writes under $OUT.
set -u
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
sed 's|/work/main/bench/filters/ten_cracks.json|bench/filters/ten_cracks.json|' \
  bench/results/bond_filter_simd_2core_zen5/filter_ratio.cpp > /tmp/filter_ratio.cpp
for tree in . .deps/old-src; do
  name=$(basename $tree)
  cmake -S $tree -B $tree/build-ab -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off \
    -DHORIZON_MPI=OFF -DCMAKE_PREFIX_PATH=/opt/deps/usr > $OUT/configure_$name.log 2>&1
  cmake --build $tree/build-ab -j 16 --target horizon_bench 2>&1 | grep -E "error"
  g++ -O2 -std=c++20 -I$tree/include -I$tree/src -I/opt/deps/usr/include /tmp/filter_ratio.cpp \
    $tree/build-ab/src/libhorizon.a -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -fopenmp -o /tmp/ratio_$name
done
lscpu > $OUT/lscpu.txt
for round in 1 2 3; do
  ./build-ab/bin/horizon_bench --sizes 100 --m 1.5 3.015 --reps 3 --cloud-points 0 > $OUT/lattice_new_$round.csv 2>&1
  .deps/old-src/build-ab/bin/horizon_bench --sizes 100 --m 1.5 3.015 --reps 3 --cloud-points 0 > $OUT/lattice_old_$round.csv 2>&1
done
for round in 1 2; do for t in 16 1; do
  echo "new: $(/tmp/ratio_. $t)" >> $OUT/filter_ratio.txt
  echo "old: $(/tmp/ratio_old-src $t)" >> $OUT/filter_ratio.txt
done; done
cat $OUT/filter_ratio.txt
