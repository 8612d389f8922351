#!/usr/bin/env bash
# The row-sorting network on the GPU machine's host CPU (AVX-512; highway 1.0 needs AES and PCLMUL
# besides x86-64-v4 to make it the static target): sortbench with the header of
# .deps/oldhdr (older) and of this tree, then the CPU A/B of device_cpu_ab.sh (oracle tests,
# horizon_bench of this tree and .deps/old-src). Usage: bash bench/gpu/device_sort_ab.sh
set -u
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
B=bench/results/sort_network_shuffles/sortbench.cpp
for v in old new; do
  inc=$([ $v = old ] && echo .deps/oldhdr || echo src)
  g++ -O2 -std=c++20 -march=x86-64-v4 -maes -mpclmul -I$inc -I/opt/deps/usr/include $B -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -o /tmp/sort_$v
done
for len in 8 16 19 32 33 48 64; do
  for v in old new; do echo -n "$v "; LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu /tmp/sort_$v $len; done
done > $OUT/sortbench.txt 2>&1
cat $OUT/sortbench.txt
[ -n "${SORT_ONLY:-}" ] || bash bench/gpu/device_cpu_ab.sh
