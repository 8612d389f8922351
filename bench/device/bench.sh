#!/usr/bin/env bash
# On the GPU machine: the benchmarks behind docs/performance (bench/results/h100*/): the GPU
# benchmark against the naive GPU cell list, then on the host's cores horizon_bench against the
# textbook cell list, the periodic box's and the radii's costs, the latency of small calls
# (idle and beside busy processes) and atomistic systems against vesin (when .deps/vesin holds
# a copy of Luthaf/vesin), all from one CUDA build.
# Usage: [PARTS="gpu cpu periodic radii latency atomistic"] [SIZES=100,200,400] [CLOUD=8000000]
#        bash bench/device/bench.sh   (writes under $OUT)
source bench/device/build.sh
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv,noheader | tee "$OUT/machine.txt"
lscpu | grep -E "Model name|^CPU\(s\)" | tee -a "$OUT/machine.txt"
for part in ${PARTS:-gpu cpu periodic radii latency atomistic}; do
  case $part in
    gpu) "$BUILD/bin/horizon_gpu_bench" --sizes "${SIZES:-100,200,400}" --cloud-points "${CLOUD:-8000000}" --reps 3 \
           ${BENCH_ARGS:-} 2> "$OUT/gpu_bench.err" | tee "$OUT/gpu_bench.csv" ;;
    cpu) "$BUILD/bin/horizon_bench" --sizes 100 --reps 3 --shuffled --cloud-points 1000000 | tee "$OUT/cpu_bench.csv" ;;
    periodic) "$BUILD/bin/horizon_periodic_bench" --reps 7 | tee "$OUT/periodic_bench.csv" ;;
    radii) "$BUILD/bin/horizon_radii_bench" --points 1000000 --reps 3 | tee "$OUT/radii_bench.csv" ;;
    latency) "$BUILD/bin/horizon_bench" --latency --busy 0,-1 | tee "$OUT/latency.csv" ;;
    atomistic) "$BUILD/bin/horizon_atomistic_bench" --reps 3 | tee "$OUT/atomistic_bench.csv" ;;
    *) echo "bench.sh: unknown part '$part'" >&2; exit 2 ;;
  esac
done
