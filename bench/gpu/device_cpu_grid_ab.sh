#!/usr/bin/env bash
# The CPU grid phase (and the whole search) of this tree against an older one (.deps/old-src),
# on the GPU machine's 16-core host: both built CPU-only, horizon_bench run alternately.
# Usage: ROUNDS=2 bash bench/gpu/device_cpu_grid_ab.sh   (writes under $OUT)
set -e
mkdir -p /opt/deps
for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
flags="-DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF -DHORIZON_TESTS=OFF -DCMAKE_PREFIX_PATH=/opt/deps/usr"
cmake -S . -B build-new $flags > /dev/null && cmake --build build-new -j 16 --target horizon_bench 2>&1 | grep error || true
cmake -S .deps/old-src -B build-old $flags > /dev/null && cmake --build build-old -j 16 --target horizon_bench 2>&1 | grep error || true
set +e
for round in $(seq "${ROUNDS:-2}"); do
  for tree in new old; do
    build-$tree/bin/horizon_bench --sizes 100 --m 1.5 3.015 --backends serial openmp --reps 5 --cloud-points 0 \
      --no-shuffled > "$OUT/${tree}_$round.csv" 2> /dev/null
    echo "$tree $round: $(grep -E 'serial|openmp' "$OUT/${tree}_$round.csv" | cut -d, -f4,6,7,9,10,12 | tr '\n' ' ')"
  done
done
