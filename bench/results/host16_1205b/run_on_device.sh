#!/usr/bin/env bash
# One device call: this tree built with CUDA; the GPU tests of the code changed (GPU required);
# then on the host's 16 cores the CPU search against the in-benchmark textbook cell list, the
# sparse-grid lookups against the tree before them (.deps/old-src), and the cost of issue 12's
# features (Verlet refresh, radii, periodic box, bond filters).
# Usage (device, .deps carried): bash bench/results/host16_1205b/run_on_device.sh
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ nvidia-smi -L; lscpu | grep "Model name"; git log --oneline -1; } > $OUT/machine.txt
(cd .deps/old-src && cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=/opt/deps/usr -DHORIZON_CUDA=off \
  -DHORIZON_PYTHON=off -DHORIZON_TESTS=OFF -DHORIZON_BENCH=OFF -DHORIZON_MPI=OFF > /dev/null && cmake --build build -j16 --target horizon > /dev/null) &
HORIZON_REQUIRE_GPU=1 timeout 150 $BUILD/bin/horizon_tests --gtest_filter="${TESTS:-Cuda.*:Partitioned*:BatchedSearch*:CellIndex.*}" > $OUT/tests.txt 2>&1
grep -E "^\[  (PASSED|FAILED) |FAILED  \]|tests ran" $OUT/tests.txt | head -20
timeout 100 $BUILD/bin/horizon_bench --sizes 100 --reps 3 --shuffled --cloud-points 1000000 > $OUT/textbook_host16.csv 2>&1
tail -3 $OUT/textbook_host16.csv
wait
CPLUS_INCLUDE_PATH=/opt/deps/usr/include LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu timeout 120 \
  bash bench/results/sparse_rows_1205/run.sh $BUILD .deps/old-src/build .deps/old-src/include > $OUT/sparse_host16.txt 2>&1
tail -40 $OUT/sparse_host16.txt
timeout 40 $BUILD/bin/horizon_verlet_bench --reps 5 > $OUT/verlet.csv 2>&1; cat $OUT/verlet.csv
timeout 60 $BUILD/bin/horizon_radii_bench --reps 3 > $OUT/radii.csv 2>&1; cat $OUT/radii.csv
timeout 40 $BUILD/bin/horizon_periodic_bench --reps 5 > $OUT/periodic.csv 2>&1; cat $OUT/periodic.csv
timeout 60 bash bench/filters/filter_cost.sh $BUILD 16 1 > $OUT/filter_cost.csv 2>&1; cat $OUT/filter_cost.csv
