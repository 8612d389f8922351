#!/usr/bin/env bash
# One call: this tree's GPU suite (GPU required) and sanitizers on the device Verlet list; A/B
# against an older tree unpacked under .deps/old-src of the device Verlet refresh, the host's
# CPU search (horizon_bench) and the GPU search (horizon_gpu_bench, lattice 200 only: with the
# clouds it passed the 600 s limit). Usage: bash bench/gpu/device_ab_search_verlet.sh (carry .deps).
source bench/gpu/device_build.sh
source bench/gpu/device_build_old.sh horizon_device_verlet_bench horizon_bench horizon_gpu_bench
(cd build-gpu && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda|Verlet|SimdTargets|Oracle|Differential|Periodic" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"; grep -E "\(Failed\)" "$OUT/gpu_tests.txt" | head
for tool in memcheck racecheck initcheck; do
  timeout 100 compute-sanitizer --tool $tool --error-exitcode 1 build-gpu/bin/horizon_tests \
    --gtest_filter='Cuda.DeviceVerlet*' > "$OUT/$tool.txt" 2>&1
  echo "$tool exit $? $(tail -1 $OUT/$tool.txt)"
done
for round in 1 2; do
  for tree in new old; do
    bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
    $bin/horizon_device_verlet_bench --sizes 100 200 > $OUT/dv_${tree}_$round.csv
    echo "== device verlet $tree $round"; tail -4 $OUT/dv_${tree}_$round.csv
  done
done
for round in 1 2; do
  for tree in new old; do
    bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
    $bin/horizon_bench --sizes 100 --m 1.5 3.015 --backends serial openmp --reps 5 --cloud-points 0 > $OUT/cpu_${tree}_$round.csv 2>&1
    echo "== cpu $tree $round"; grep -E "serial|openmp" $OUT/cpu_${tree}_$round.csv | grep "^lattice," | cut -d, -f4,6,7,9,10,11,16
  done
done
for tree in new old; do
  bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
  $bin/horizon_gpu_bench --sizes 200 --m 1.5,3.015 --cloud-points 0 --reps 5 --cpu-max-n 0 --no-host > $OUT/gpu_${tree}.csv 2>&1
  echo "== gpu $tree"; grep -v "^#" $OUT/gpu_${tree}.csv | cut -d, -f1,2,4,6,8,9,10,12
done
