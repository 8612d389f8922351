#!/usr/bin/env bash
# One device call: this tree (the host path page-locks the lists' pool's blocks it reuses and
# copies into them by DMA alone, src/backends/cuda/pinned_blocks.cuh) against
# .deps/old-src (main d331578): the GPU suite and the pool's tests, then the host path A/B.
# Usage (device, carry [".deps"]): [ROUNDS=3] [SIZES=...] bash bench/results/pinned_lists_1206/run_on_device.sh
# (When it ran, these steps were written out here; bench/gpu/device_host_path_ab.sh now holds them,
# except that the bench's per-call lines, added later, also go to errors.txt.)
TESTS="cuda|Cuda|Buffer|StagingChunks" source bench/gpu/device_host_path_ab.sh
