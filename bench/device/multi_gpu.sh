#!/usr/bin/env bash
# The multi-GPU study (the thesis's Table 5.2): the partitioned search's tests with the GPUs
# required; the speed-up predicted from parts timed alone on GPU 0 (horizon_parts_bench, any
# machine); where several GPUs are visible, the speed-up measured on 1, 2, 4, 8 of them
# (bench/multi_gpu/run_multi_gpu.sh; DEVICES=0,0 cuts the work into parts on one GPU). Plots.
# Usage: [SIZES="100 200 400"] [PARTS=1,2,4,8] [GPUS="1 2 4 8"] [DEVICES=0,0] [MEASURE=0|1]
#        bash bench/device/multi_gpu.sh   (writes under $OUT)
source bench/device/build.sh
nvidia-smi -L | tee "$OUT/gpus.txt"
HORIZON_REQUIRE_GPU=1 "$BUILD/bin/horizon_tests" --gtest_filter='Partitioned*' > "$OUT/tests.log" 2>&1
tail -3 "$OUT/tests.log"
sizes=${SIZES:-100 200 400}
"$BUILD/bin/horizon_parts_bench" --sizes "${sizes// /,}" --parts "${PARTS:-1,2,4,8}" \
  > "$OUT/parts_bench.csv" 2> "$OUT/parts_bench.log"
cat "$OUT/parts_bench.csv"
python3 bench/multi_gpu/plot_parts.py "$OUT/parts_bench.csv" "$OUT" || echo "no plots here: plot_parts.py runs on the CSV anywhere"
if [ "${MEASURE:-$(( $(nvidia-smi -L | wc -l) > 1 ))}" = 1 ]; then
  SIZES="$sizes" bash bench/multi_gpu/run_multi_gpu.sh "$BUILD" "$OUT/study"
  python3 bench/multi_gpu/plot_multi_gpu.py "$OUT/study/multi_gpu.jsonl" "$OUT/study" && mv "$OUT"/study/* "$OUT"/
fi
