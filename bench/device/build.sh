#!/usr/bin/env bash
# Builds horizon with CUDA on the GPU machine (Ubuntu 24.04, CUDA 13, no network). That image
# lacks highway and nanoflann: `make device-deps` downloads Debian's packages into .deps/ here,
# and every device call carries .deps and sources this script, which unpacks them into /opt/deps.
# Usage: source bench/device/build.sh   (sets BUILD, LD_LIBRARY_PATH; CMAKE_ARGS adds options)
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
