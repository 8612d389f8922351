#!/usr/bin/env bash
# On the GPU machine: per-kernel durations (Nsight Compute, duration only) of device-resident
# searches and of the naive anchor, lattice n = 200, both horizons.
# Usage: bash bench/gpu/device_profile.sh  (writes under $OUT)
source bench/gpu/device_build.sh
ncu --clock-control none --metrics gpu__time_duration.sum --csv \
  "$BUILD/bin/horizon_gpu_bench" --sizes "${PROFILE_SIZES:-200}" --cloud-points 0 --reps 1 --no-host \
  > "$OUT/ncu.csv" 2> "$OUT/ncu.err"
