#!/usr/bin/env bash
# On a one-GPU machine: every test with the GPU required, then the multi-GPU code paths on that
# one GPU (issue 10): the study script with DEVICES=0,0,0 runs the one-process driver on 2 and 3
# parts and mpirun with 2 and 3 ranks sharing the GPU, and compares every list (n <= 200) byte
# for byte with the one-GPU list, which is compared here with the CPU serial list too.
# Usage: bash bench/gpu/device_one_gpu_many_parts.sh   (writes under $OUT)
source bench/gpu/device_build.sh
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader | tee "$OUT/gpu.txt"
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 ctest -j 8 --output-on-failure) > "$OUT/ctest.log" 2>&1
grep -E "tests passed|tests failed|Failed|\*\*\*" "$OUT/ctest.log" | tail -15
bin="$BUILD/bin/horizon"
"$bin" search lattice:100 --horizon 0.3015 --backend cuda --out /tmp/gpu1 --quiet
"$bin" search lattice:100 --horizon 0.3015 --backend serial --out /tmp/cpu1 --quiet
cmp /tmp/gpu1.offsets.npy /tmp/cpu1.offsets.npy && cmp /tmp/gpu1.indices.npy /tmp/cpu1.indices.npy \
  && echo "lattice 100, m = 3.015: one GPU list identical to the CPU serial list" | tee "$OUT/gpu_vs_cpu.txt"
which mpirun && mpirun --version | head -1
SIZES="${SIZES:-50 100 200}" GPUS="1 2 3" DEVICES=0,0,0 REPS=1 \
  bash bench/multi_gpu/run_multi_gpu.sh "$BUILD" /tmp/mg 2> "$OUT/study.err"; echo "study exit $?"
tail -8 "$OUT/study.err"
python3 bench/multi_gpu/plot_multi_gpu.py /tmp/mg/multi_gpu.jsonl /tmp/mg/plots > "$OUT/plot.log" 2>&1; echo "plot exit $?"
tail -5 "$OUT/plot.log"
cp /tmp/mg/multi_gpu.jsonl /tmp/mg/identical.txt "$OUT/" 2>/dev/null
cat /tmp/mg/plots/table_5_2.md 2>/dev/null | tee "$OUT/table_5_2.md"
