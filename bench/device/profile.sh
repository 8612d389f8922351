#!/usr/bin/env bash
# On the GPU machine: per-kernel durations (Nsight Compute, duration only) of device-resident
# searches and of the naive anchor, lattice n = 200, both horizons; with DETAIL=1 also the
# full section set of the m = 3.015 count and fill kernels (one launch each).
# Usage: [PROFILE_SIZES=200] [DETAIL=1] bash bench/device/profile.sh  (writes under $OUT)
source bench/device/build.sh
ncu --clock-control none --metrics gpu__time_duration.sum --csv \
  "$BUILD/bin/horizon_gpu_bench" --sizes "${PROFILE_SIZES:-200}" --cloud-points 0 --reps 1 --no-host \
  > "$OUT/ncu.csv" 2> "$OUT/ncu.err"
python3 - "$OUT/ncu.csv" <<'PY' | tee "$OUT/ncu_kernels.txt"
import csv, sys
rows = [r for r in csv.reader(l for l in open(sys.argv[1]) if l.startswith('"'))][1:]
for r in rows:
    print(f"{r[0]:>4} {float(r[-1].replace(',', '')) / 1e6:9.3f} ms  {r[4][:110]}")
PY
if [ "${DETAIL:-0}" = 1 ]; then
  # The full section set of the m = 3.015 search's count and fill (the fourth count launch is its first).
  for kernel in "count_families --launch-skip 3" "cell_families --launch-skip 0"; do
    set -- $kernel
    ncu --clock-control none --set full --import-source no --kernel-name regex:"$1" $2 $3 --launch-count 1 \
      "$BUILD/bin/horizon_gpu_bench" --sizes "${PROFILE_SIZES:-200}" --cloud-points 0 --reps 1 --no-host \
      > "$OUT/ncu_detail_$1.txt" 2>&1
  done
fi
