#!/usr/bin/env bash
# One device call: this tree (copies through staging cut into chunks that halve towards both
# ends, src/backends/cuda/staging_chunks.hpp; small copies split over every core) against
# .deps/old-src (main before it). Both built with CUDA; the GPU suite and the copy tests (GPU
# required) on this one; horizon_gpu_bench of both trees alternating, ROUNDS rounds.
# Usage (device, carry [".deps"]): [ROUNDS=3] bash bench/results/staging_ramp_1206/run_on_device.sh
# (Its summary printer, inline when the call ran, is now bench/gpu/host_path_summary.py: same output.)
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
source bench/gpu/device_build_old.sh horizon_gpu_bench
{ nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"; } > $OUT/machine.txt
(cd build-gpu && HORIZON_REQUIRE_GPU=1 timeout 240 ctest -j 8 -R "cuda|Cuda|ParallelCopy|StagingChunks" > $OUT/gpu_tests.txt 2>&1)
grep -E "tests passed|tests failed" $OUT/gpu_tests.txt; grep -E "\(Failed\)|Timeout" $OUT/gpu_tests.txt | head
ARGS="--sizes ${SIZES:-100,200,400} --cloud-points 8000000 --reps 5 --cpu-max-n 0"
for round in $(seq ${ROUNDS:-3}); do for tree in new old; do
  bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
  timeout 100 $bin/horizon_gpu_bench $ARGS > $OUT/${tree}_$round.csv 2> $OUT/${tree}_$round.err
done; done
python3 bench/gpu/host_path_summary.py $OUT | tee $OUT/summary.txt
