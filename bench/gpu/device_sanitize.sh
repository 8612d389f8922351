#!/usr/bin/env bash
# On the GPU machine: compute-sanitizer memcheck, racecheck and initcheck over searches that take
# every fill kernel (short rows, per cell, per point + row sorts of every length), full and half
# lists, 2-D, k = 1-3. Usage: bash bench/gpu/device_sanitize.sh  (writes $OUT/sanitize.log)
source bench/gpu/device_build.sh
python3 - <<'PY'
import numpy as np
rng = np.random.default_rng(1)
blob = 0.01 * rng.standard_normal((3000, 3)) + 5.0  # one dense blob: stencils too wide to stage
spread = 10.0 * rng.random((2000, 3))
np.save("/tmp/blob.npy", np.vstack([blob, spread]))
np.save("/tmp/plane.npy", 10.0 * rng.random((20000, 2)))
PY
cli="$BUILD/bin/horizon search"
cases=("lattice:20 --horizon 0.75" "lattice:20 --horizon 1.5 --half" "lattice:20 --horizon 3.015" "lattice:16 --horizon 2.2 --cells-per-horizon 2"
       "lattice:12 --horizon 2.5 --metric l1 --cells-per-horizon 3" "/tmp/blob.npy --horizon 0.5"
       "/tmp/blob.npy --horizon 0.5 --half" "/tmp/plane.npy --horizon 0.2" "/tmp/plane.npy --horizon 0.4 --half")
for tool in memcheck racecheck initcheck; do
  for c in "${cases[@]}"; do
    echo "== $tool: $c" >> "$OUT/sanitize.log"
    compute-sanitizer --tool $tool $cli $c --backend cuda >> "$OUT/sanitize.log" 2>&1
    echo "$tool | $c | $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' "$OUT/sanitize.log" | tail -1)"
  done
done
