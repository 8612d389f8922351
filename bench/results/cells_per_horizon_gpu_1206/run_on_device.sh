#!/usr/bin/env bash
# One call on the GPU machine: build, the GPU suite (GPU required), then horizon_gpu_bench
# device-resident only at k = 1, 2, 3 (cells per horizon), alternating, ROUNDS rounds.
# The naive kernel (k = 1) runs in the k = 1 runs; compare k = 2, 3 with the k = 1 run next to it.
# Usage (repository root, carry [".deps"]): bash bench/results/cells_per_horizon_gpu_1206/run_on_device.sh
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"; } > $OUT/machine.txt
(cd "$BUILD" && HORIZON_REQUIRE_GPU=1 timeout 200 ctest -j 16 -R "cuda|Cuda|Buffer|StagingChunks" > $OUT/gpu_tests.txt 2>&1)
grep -E "tests passed|tests failed" $OUT/gpu_tests.txt; grep -E "\(Failed\)|Timeout" $OUT/gpu_tests.txt | head
for round in $(seq ${ROUNDS:-2}); do for k in ${KS:-1 2 3}; do
  timeout 120 "$BUILD/bin/horizon_gpu_bench" --no-host --sizes ${SIZES:-100,200,400} --cloud-points ${CLOUD:-8000000} \
    --reps 5 --k $k > $OUT/k${k}_$round.csv 2>> $OUT/errors.txt
  echo "k=$k round $round"; cut -d, -f1,2,4,6,10,12 $OUT/k${k}_$round.csv
done; done
