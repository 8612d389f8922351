#!/usr/bin/env bash
# Setup of a CPU A/B on the GPU machine's 16-core host: builds this tree (CPU only) and the older
# one unpacked under .deps/old-src (CPU only, in the background), writes $OUT/machine.txt, runs
# the search's oracle tests of this tree ($OUT/tests.txt), then compiles the phase driver
# (bench/results/cpu_phases_1205/phase_bench.cpp) against both: /tmp/pb_new and /tmp/pb_old.
# Usage (device, carry [".deps"]), from a device script:
#   [TEST_FILTER=...] [OLD_TARGETS="--target horizon"] source bench/cpu/device_host_ab_setup.sh
# Sets BUILD (this tree's build) and OLD_BIN (the old tree's bin folder).
CMAKE_ARGS="-DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ lscpu | grep -E "Model name|^CPU\(s\)|Flags" | cut -c1-300; nvidia-smi -L; } > $OUT/machine.txt
(cd .deps/old-src && cmake -S . -B build-host -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=/opt/deps/usr -DHORIZON_CUDA=off \
  -DHORIZON_PYTHON=off -DHORIZON_TESTS=OFF -DHORIZON_BENCH=ON -DHORIZON_MPI=OFF > /dev/null \
  && cmake --build build-host -j16 ${OLD_TARGETS:-} > /dev/null) &
timeout 200 $BUILD/bin/horizon_tests \
  --gtest_filter="${TEST_FILTER:-SimdTargets.*:*Search*:Grid.*:Oracle*:CellIndex.*:*Half*:*Unsorted*:*Radii*}" > $OUT/tests.txt 2>&1
grep -E "^\[  (PASSED|FAILED) |FAILED  \]" $OUT/tests.txt | head -20
wait
OLD_BIN=.deps/old-src/build-host/bin
I="-I/opt/deps/usr/include"; L="-L/opt/deps/usr/lib/x86_64-linux-gnu"
g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc $I bench/results/cpu_phases_1205/phase_bench.cpp $BUILD/src/libhorizon.a $L -lhwy -o /tmp/pb_new
g++ -O2 -std=c++20 -fopenmp -I.deps/old-src/include -I.deps/old-src/src $I bench/results/cpu_phases_1205/phase_bench.cpp \
  .deps/old-src/build-host/src/libhorizon.a $L -lhwy -o /tmp/pb_old
