#!/usr/bin/env bash
# Host->host A/B on the GPU machine: builds this tree and an older one (unpacked under
# .deps/old-src) with CUDA, runs TESTS (a ctest regex, GPU required) on this one, then
# horizon_gpu_bench of both trees alternating, ROUNDS rounds, host path only, and prints the
# host path's figures (bench/gpu/host_path_summary.py). Stderr goes to errors.txt, each line
# prefixed by its tree and round (the bench's per-call phases among it).
# Usage (repository root, carry [".deps"]):
#   TESTS=regex [ROUNDS=3] [SIZES=100,200,400] [CLOUD=8000000] bash bench/gpu/device_host_path_ab.sh
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
source bench/gpu/device_build_old.sh horizon_gpu_bench
{ nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"; } > $OUT/machine.txt
(cd build-gpu && HORIZON_REQUIRE_GPU=1 timeout 240 ctest -j 8 -R "$TESTS" > $OUT/gpu_tests.txt 2>&1)
grep -E "tests passed|tests failed" $OUT/gpu_tests.txt; grep -E "\(Failed\)|Timeout" $OUT/gpu_tests.txt | head
ARGS="--sizes ${SIZES:-100,200,400} --cloud-points ${CLOUD:-8000000} --reps 5 --cpu-max-n 0"
for round in $(seq ${ROUNDS:-3}); do for tree in new old; do
  bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
  timeout 100 $bin/horizon_gpu_bench $ARGS > $OUT/${tree}_$round.csv 2> /tmp/bench.err
  sed "s/^/${tree}_$round: /" /tmp/bench.err >> $OUT/errors.txt
done; done
rm -f $OUT/configure_old.log  # at most 8 files come back
python3 bench/gpu/host_path_summary.py $OUT | tee $OUT/summary.txt
