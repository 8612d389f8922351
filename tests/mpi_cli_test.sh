#!/usr/bin/env bash
# mpirun -np 3 horizon search ... --exchange X writes byte-for-byte the files of a serial run.
# Usage: mpi_cli_test.sh HORIZON_BINARY MPIEXEC WORK_DIR
set -eu
horizon="$1"; mpiexec="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"; cd "$work"
"$horizon" generate clusters --count 20000 --clusters 7 --sigma 0.6 --out points.npy
"$horizon" search points.npy --horizon 0.25 --backend serial --out serial --quiet
for exchange in thesis halo overlap; do
  for decomposition in rcb brick; do
    "$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --horizon 0.25 --exchange "$exchange" \
      --decomposition "$decomposition" --out "$exchange" --json --quiet > "$exchange.json"
    grep -q '"ranks":3' "$exchange.json"
    cmp serial.offsets.npy "$exchange.offsets.npy"
    cmp serial.indices.npy "$exchange.indices.npy"
  done
done
# A bad input fails on every rank with status 2 and one clear message.
set +e
"$mpiexec" --oversubscribe -np 2 "$horizon" search missing.npy --horizon 1 --exchange halo 2> error.txt
status=$?
set -e
[ "$status" -ne 0 ] && grep -q "missing.npy: cannot open" error.txt
echo "mpirun CLI: all strategies identical to serial"
