#!/usr/bin/env bash
# The two ways a distributed search writes its list, at 1..16 ranks: gather (rows sent to rank 0,
# which writes the files) and parallel (every rank writes its rows through MPI-IO). Each run is
# checked byte for byte against the serial files. OMP threads per rank = cores / ranks.
# Appends one JSON line per run to OUT.jsonl (horizon's --json plus n, m, ranks, writer).
# Usage: bench/mpi/writer_bench.sh BUILD_DIR OUT.jsonl WORK_DIR [RANKS="1 2 4 8 16"] [PROBLEMS="200:1.5 150:3.015"]
set -eu
bin="$1/bin/horizon"; out="$2"; work="$3"; mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
cores=$(nproc)
for problem in ${PROBLEMS:-200:1.5 150:3.015}; do
  n=${problem%%:*}; m=${problem##*:}; h=$(python3 -c "print($m * 10 / $n)")
  "$bin" search "lattice:$n" --horizon "$h" --backend openmp --out "$work/serial" --quiet
  for p in ${RANKS:-1 2 4 8 16}; do
    for writer in gather parallel; do
      line=$(OMP_NUM_THREADS=$((cores / p > 0 ? cores / p : 1)) mpirun --oversubscribe --bind-to none -np "$p" \
        "$bin" search "lattice:$n" --horizon "$h" --backend openmp --exchange halo --writer "$writer" \
        --out "$work/ranks" --json --quiet)
      cmp "$work/serial.offsets.npy" "$work/ranks.offsets.npy"
      cmp "$work/serial.indices.npy" "$work/ranks.indices.npy"
      echo "${line/#\{/{\"n\":$n,\"m\":$m,}" >> "$out"
      echo "$line" | python3 -c "import json,sys; r=json.load(sys.stdin); s=r['seconds']; print($n, $m, $p, '$writer', r['neighbors'], 'gather', round(s['gather'],3), 'write', round(s['write'],3))"
    done
  done
  rm -f "$work"/serial.* "$work"/ranks.*
done
