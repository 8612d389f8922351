#!/usr/bin/env bash
# Builds targets of an older tree, unpacked under .deps/old-src, with CUDA, for an A/B against
# this one. Usage (after bench/gpu/device_build.sh): source bench/gpu/device_build_old.sh TARGET...
# (sets OLD, the build folder; writes $OUT/configure_old.log)
OLD=.deps/old-src/build-gpu
cmake -S .deps/old-src -B $OLD -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=on -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF \
  -DCMAKE_PREFIX_PATH=/opt/deps/usr -DCMAKE_CUDA_ARCHITECTURES=90 > $OUT/configure_old.log 2>&1
cmake --build $OLD -j "$(nproc)" --target "$@" 2>&1 | grep -E "error"
