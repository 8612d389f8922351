#!/usr/bin/env bash
# Builds horizon with CUDA on the GPU machine (Ubuntu 24.04, CUDA 13): unpacks the carried
# Debian packages that image lacks (highway, nanoflann) into /opt/deps, then configures.
# Usage: source bench/gpu/device_build.sh   (sets BUILD, LD_LIBRARY_PATH)
set -e
mkdir -p /opt/deps
for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
export CMAKE_PREFIX_PATH=/opt/deps/usr  # also for the nested CMake of pip install
export BUILD=${BUILD:-build-gpu}
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=on \
  -DCMAKE_PREFIX_PATH=/opt/deps/usr -DCMAKE_CUDA_ARCHITECTURES=90 ${CMAKE_ARGS:-} > "$BUILD.configure.log" 2>&1 \
  || { cat "$BUILD.configure.log"; return 1 2>/dev/null || exit 1; }
cmake --build "$BUILD" -j "$(nproc)" 2>&1 | grep -E "error|warning: unused" || true
set +e
