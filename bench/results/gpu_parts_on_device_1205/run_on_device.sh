#!/usr/bin/env bash
# One device call: this tree and the one under .deps/old-src built with CUDA; the partitioned
# (multi-GPU driver) and CUDA tests of this one with the GPU required; then host->host through
# the CLI, one GPU (--device 0) against two parts on it (--gpus 0,0), both trees alternating.
# Usage (device, .deps carried): bash bench/results/gpu_parts_on_device_1205/run_on_device.sh
source bench/gpu/device_build.sh
source bench/gpu/device_build_old.sh horizon_cli
HORIZON_REQUIRE_GPU=1 build-gpu/bin/horizon_tests --gtest_filter="${TESTS:-Partitioned*:Cuda.*}" > $OUT/tests.txt 2>&1
grep -E "PASSED|FAILED" $OUT/tests.txt | head
nvidia-smi -L > $OUT/gpu.txt; lscpu | grep "Model name" >> $OUT/gpu.txt
for n in ${SIZES:-200 400}; do for m in 1.5 3.015; do for rep in $(seq ${REPS:-2}); do for tree in new old; do
  bin=build-gpu/bin/horizon; [ $tree = old ] && bin=$OLD/bin/horizon
  for mode in "--device 0" "--gpus 0,0"; do
    h=$(python3 -c "print($m * 10 / $n)")
    $bin search lattice:$n --horizon $h --backend cuda $mode --json --quiet | python3 -c "
import json, sys; d = json.load(sys.stdin); s = d['seconds']
parts = ' '.join('%.3f' % g['seconds'] for g in d.get('gpus', []))
print('$tree n=$n m=$m $mode rep=$rep entries %d total %.3f partition %s assemble %s parts [%s]' % (d['neighbors'],
      s.get('search', 0) + s.get('grid', 0), s.get('partition'), s.get('assemble'), parts))"
  done
done; done; done; done 2>&1 | tee $OUT/cli.txt
