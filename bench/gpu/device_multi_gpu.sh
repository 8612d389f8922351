#!/usr/bin/env bash
# On a machine with several GPUs: the partitioned search test with the GPUs required, then the
# lattice problems of DESIGN.md host->host on 1 and on every GPU through the one-process driver
# (--gpus; partition and assembly included), and one rank per GPU under mpirun (halo exchange).
# Usage: [SIZES="200 300 400"] bash bench/gpu/device_multi_gpu.sh  (writes $OUT/multi_gpu.jsonl)
source bench/gpu/device_build.sh
gpus=$(nvidia-smi -L | wc -l)
nvidia-smi -L | tee "$OUT/gpus.txt"
HORIZON_REQUIRE_GPU=1 "$BUILD/bin/horizon_tests" --gtest_filter='Partitioned*:Cuda.*' > "$OUT/tests.log" 2>&1
tail -3 "$OUT/tests.log"
for n in ${SIZES:-200 300 400}; do
  for m in 1.5 3.015; do
    h=$(python3 -c "print($m * 10 / $n)")
    for g in 1 $gpus; do
      echo "{\"n\": $n, \"m\": $m, \"gpus\": $g, \"mode\": \"one-process\", \"result\": $("$BUILD/bin/horizon" search lattice:$n --horizon $h --backend cuda --gpus $g --json --quiet)}" \
        | tee -a "$OUT/multi_gpu.jsonl" | python3 -c "import json,sys; r=json.loads(sys.stdin.read()); print(r['n'], r['m'], r['gpus'], r['result']['neighbors'], round(r['result']['seconds']['search'],3), r['result'].get('imbalance'))"
    done
  done
done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
n=${MPI_N:-400}; h=$(python3 -c "print(3.015 * 10 / $n)")
mpirun --oversubscribe -np "$gpus" "$BUILD/bin/horizon" search lattice:$n --horizon $h --backend cuda --json --quiet \
  > "$OUT/mpi_rank_per_gpu.json" 2> "$OUT/mpi.err"; cat "$OUT/mpi_rank_per_gpu.json" | head -c 600; tail -3 "$OUT/mpi.err"
