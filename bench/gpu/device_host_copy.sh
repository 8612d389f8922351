#!/usr/bin/env bash
# On the GPU machine: which device -> pageable-host copy reaches PCIe speed (host_copy_bench.cu),
# then, unless BENCH=0, the GPU benchmark. Usage: [GIB="4 16"] bash bench/gpu/device_host_copy.sh
nvcc -O3 -arch=sm_90 -Xcompiler -fopenmp,-mavx2 bench/gpu/host_copy_bench.cu -o /tmp/host_copy_bench || exit 1
uname -r > "$OUT/host_copy.csv"
OMP_PROC_BIND=spread /tmp/host_copy_bench ${GIB:-4 16} | tee -a "$OUT/host_copy.csv"
if [ "${BENCH:-1}" = 1 ]; then TESTS=0 bash bench/gpu/device_bench.sh; fi
