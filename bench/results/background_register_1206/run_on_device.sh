#!/usr/bin/env bash
# Device call: this tree (a list block registered on a thread of its own while the call that
# starts it copies through staging; src/backends/cuda/pinned_blocks.cuh) against .deps/old-src
# (main 0fc3a1e: registered inside that call, which then takes about twice a repeated one).
# Prints, per tree and problem, the host calls 1-3 phases: call 1 is the one that registers,
# call 2 the first that may find the block registered. machine.txt gets the memory zones
# (long-term pinning first migrates pages out of a movable zone) and the migration counters.
# Usage (repository root, .deps/old-src = main unpacked, carry [".deps"]):
#   bash bench/results/background_register_1206/run_on_device.sh
counters() { grep -E '^(pgmigrate_success|pgmigrate_fail|compact_stall|thp_fault_alloc|thp_collapse_alloc) ' /proc/vmstat; }
counters > /tmp/vmstat_before
ROUNDS=${ROUNDS:-2} SIZES=${SIZES:-200,400} CLOUD=0 TESTS="cuda|Cuda|Buffer" source bench/gpu/device_host_path_ab.sh
{ echo "# zones (pages)"; awk '/^Node/ {zone=$4} /present/ {print zone, "present", $2} /managed/ {print zone, "managed", $2}' /proc/zoneinfo
  echo "# vmstat before"; cat /tmp/vmstat_before; echo "# after"; counters; } >> $OUT/machine.txt
grep -E "call [1-3]:" $OUT/errors.txt | tee -a $OUT/summary.txt
