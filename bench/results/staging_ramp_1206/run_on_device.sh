#!/usr/bin/env bash
# One device call: this tree (copies through staging cut into chunks that halve towards both
# ends, src/backends/cuda/staging_chunks.hpp; small copies split over every core) against
# .deps/old-src (main before it). Both built with CUDA; the GPU suite and the copy tests (GPU
# required) on this one; horizon_gpu_bench of both trees alternating, ROUNDS rounds.
# Usage (device, carry [".deps"]): [ROUNDS=3] bash bench/results/staging_ramp_1206/run_on_device.sh
# (When it ran, these steps were written out here, each run's stderr in its own .err file;
# bench/gpu/device_host_path_ab.sh now holds them, stderr to errors.txt.)
TESTS="cuda|Cuda|ParallelCopy|StagingChunks" source bench/gpu/device_host_path_ab.sh
