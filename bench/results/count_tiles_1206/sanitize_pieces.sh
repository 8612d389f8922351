#!/usr/bin/env bash
# One device call: the GPU suite (GPU required) on this tree, then compute-sanitizer memcheck,
# racecheck and initcheck over the host path's pieces (row_pieces.cuh's piece_positions in every
# host search; a list of 295 MB filled in two pieces; batches two on the GPU at once).
# Usage (device, .deps carried): bash bench/results/count_tiles_1206/sanitize_pieces.sh
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
nvidia-smi -L > $OUT/machine.txt
(cd $BUILD && HORIZON_REQUIRE_GPU=1 timeout 240 ctest -j 8 -R "cuda|Cuda" > $OUT/gpu_tests.txt 2>&1)
grep -E "tests passed|tests failed" $OUT/gpu_tests.txt; grep -E "\(Failed\)|Timeout" $OUT/gpu_tests.txt | head
cases=("$BUILD/bin/horizon search lattice:160 --horizon 0.15 --backend cuda"
       "$BUILD/bin/horizon search lattice:20 --horizon 0.3015 --backend cuda --half"
       "$BUILD/bin/horizon_tests --gtest_filter=Cuda.BatchedHostSearchEqualsSerial:Cuda.BatchesOfSingleLongRowsEqualSerial")
for tool in memcheck racecheck initcheck; do
  for c in "${cases[@]}"; do
    echo "== $tool: $c" >> $OUT/sanitize.log
    HORIZON_REQUIRE_GPU=1 timeout 150 compute-sanitizer --tool $tool $c >> $OUT/sanitize.log 2>&1
    echo "$tool rc $? | ${c#$BUILD/bin/} | $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' $OUT/sanitize.log | tail -1)"
  done
done
