#!/usr/bin/env bash
# One call on the GPU machine: build with CUDA, the GPU suite with the GPU required, then the
# count pass alone on the host CPU (each pair once vs every full stencil, one thread) and the
# whole search of this tree and of .deps/old-src (built without CUDA), alternating.
# Usage: bash bench/gpu/device_count_pairs.sh  (writes under $OUT)
source bench/gpu/device_build.sh
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 8 -R "cuda|Cuda|GpuMaxMemory" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"
P=bench/results/count_each_pair_once
CUDA_LIB="-L/usr/local/cuda/lib64 -L/usr/local/cuda/targets/x86_64-linux/lib -lcudart"
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc -I/opt/deps/usr/include $P/count_probe.cpp "$BUILD/src/libhorizon.a" \
  -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy $CUDA_LIB -o /tmp/count_probe
g++ -O2 -std=c++20 -fopenmp -Iinclude -I/opt/deps/usr/include $P/search_probe.cpp "$BUILD/src/libhorizon.a" \
  -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy $CUDA_LIB -o /tmp/search_new
for k in lattice random clustered; do for m in 1.5 3.015; do /tmp/count_probe $k $m 7; done; done > "$OUT/count_pass.txt"
cat "$OUT/count_pass.txt"
if [ -d .deps/old-src ]; then
  cmake -S .deps/old-src -B .deps/old-src/build-ab -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off \
    -DHORIZON_MPI=OFF -DHORIZON_TESTS=OFF -DHORIZON_BENCH=OFF -DCMAKE_PREFIX_PATH=/opt/deps/usr > "$OUT/configure_old.log" 2>&1
  cmake --build .deps/old-src/build-ab -j "$(nproc)" 2>&1 | grep -E "error"
  g++ -O2 -std=c++20 -fopenmp -I.deps/old-src/include -I/opt/deps/usr/include $P/search_probe.cpp \
    .deps/old-src/build-ab/src/libhorizon.a -L/opt/deps/usr/lib/x86_64-linux-gnu -lhwy -o /tmp/search_old
  for r in 1 2 3; do for k in lattice random; do for m in 1.5 3.015; do for t in 1 16; do for v in old new; do
    echo "$r $k $m t$t $v: $(/tmp/search_$v $k $m $t 7 2>&1)"; done; done; done; done; done > "$OUT/whole_search_ab.txt"
  tail -4 "$OUT/whole_search_ab.txt"
fi
