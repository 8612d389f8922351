#!/usr/bin/env bash
# Device call: this tree (a list block registered on a thread of its own while the call that
# starts it copies through staging; src/backends/cuda/pinned_blocks.cuh) against .deps/old-src
# (main 0fc3a1e: registered inside that call, which then takes about twice a repeated one).
# Prints, per tree and problem, the first three host calls' phases: the second is the one that
# registers, the third the first that may find the block registered.
# Usage (repository root, .deps/old-src = main unpacked, carry [".deps"]):
#   bash bench/results/background_register_1206/run_on_device.sh
ROUNDS=${ROUNDS:-2} SIZES=${SIZES:-200,400} CLOUD=0 TESTS="cuda|Cuda|Buffer" source bench/gpu/device_host_path_ab.sh
grep -E "call [0-3]:" $OUT/errors.txt | grep -v "call 0:" | tee -a $OUT/summary.txt
