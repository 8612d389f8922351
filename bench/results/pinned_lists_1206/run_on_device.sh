#!/usr/bin/env bash
# One device call: this tree (the host path page-locks the lists' pool's blocks it reuses and
# copies into them by DMA alone, src/backends/cuda/pinned_blocks.cuh) against
# .deps/old-src (main d331578). Both built with CUDA; the GPU suite and the copy tests (GPU
# required) on this one; horizon_gpu_bench of both trees alternating, ROUNDS rounds.
# Usage (device, carry [".deps"]): [ROUNDS=3] bash bench/results/pinned_lists_1206/run_on_device.sh
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
source bench/gpu/device_build_old.sh horizon_gpu_bench
{ nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"; } > $OUT/machine.txt
(cd build-gpu && HORIZON_REQUIRE_GPU=1 timeout 240 ctest -j 8 -R "${TESTS:-cuda|Cuda|Buffer|StagingChunks}" > $OUT/gpu_tests.txt 2>&1)
grep -E "tests passed|tests failed" $OUT/gpu_tests.txt; grep -E "\(Failed\)|Timeout" $OUT/gpu_tests.txt | head
ARGS="--sizes ${SIZES:-100,200,400} --cloud-points ${CLOUD:-8000000} --reps 5 --cpu-max-n 0"
for round in $(seq ${ROUNDS:-3}); do for tree in new old; do
  bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
  timeout 100 $bin/horizon_gpu_bench $ARGS > $OUT/${tree}_$round.csv 2>> $OUT/errors.txt
done; done
rm -f $OUT/configure_old.log  # at most 8 files come back
python3 bench/gpu/host_path_summary.py $OUT | tee $OUT/summary.txt
