#!/usr/bin/env bash
# The multi-GPU study (the thesis's Table 5.2): the partitioned search's tests with the GPUs
# required, then bench/multi_gpu/run_multi_gpu.sh over the lattice problems of DESIGN.md on
# 1, 2, 4, 8 GPUs (those visible; DEVICES=0,0 cuts the work into parts on one GPU), and its plots.
# Usage: [SIZES="100 200 400"] [GPUS="1 2 4 8"] [DEVICES=0,0] bash bench/device/multi_gpu.sh   (writes under $OUT)
source bench/device/build.sh
nvidia-smi -L | tee "$OUT/gpus.txt"
HORIZON_REQUIRE_GPU=1 "$BUILD/bin/horizon_tests" --gtest_filter='Partitioned*:Cuda.*' > "$OUT/tests.log" 2>&1
tail -3 "$OUT/tests.log"
SIZES=${SIZES:-100 200 400} bash bench/multi_gpu/run_multi_gpu.sh "$BUILD" "$OUT/study"
python3 bench/multi_gpu/plot_multi_gpu.py "$OUT/study/multi_gpu.jsonl" "$OUT/study" && mv "$OUT"/study/* "$OUT"/
