#!/usr/bin/env bash
# One device call: this tree built with CUDA, the whole test binary with the GPU required,
# then the CPU search against the in-benchmark textbook cell list on the host's cores.
# Usage (device, .deps carried): bash bench/results/textbook_anchor_1205/run_on_device.sh
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
nvidia-smi -L > $OUT/gpu.txt; lscpu | grep "Model name" >> $OUT/gpu.txt
HORIZON_REQUIRE_GPU=1 timeout 200 $BUILD/bin/horizon_tests --gtest_filter="${TESTS:-*}" > $OUT/tests.txt 2>&1
grep -E "^\[  (PASSED|FAILED) |FAILED  \]|tests ran" $OUT/tests.txt | head -20
timeout 120 $BUILD/bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/host16.csv 2>&1
tail -3 $OUT/host16.csv
