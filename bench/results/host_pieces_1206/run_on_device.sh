#!/usr/bin/env bash
# One device call: this tree (the host path fills a list that fits on the GPU in pieces, each
# copied back while the next fills; every fill visits only the sorted positions of its rows)
# against .deps/old-src (main before it). Both built with CUDA; the GPU suite (GPU required) on
# this one; horizon_gpu_bench of both trees alternating, two rounds.
# Usage (device, .deps carried): bash bench/results/host_pieces_1206/run_on_device.sh
mkdir -p /opt/deps; for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
(cd .deps/old-src && cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=on -DHORIZON_PYTHON=off \
  -DHORIZON_MPI=OFF -DCMAKE_PREFIX_PATH=/opt/deps/usr -DCMAKE_CUDA_ARCHITECTURES=90 > /dev/null \
  && cmake --build build-gpu -j6 --target horizon_gpu_bench 2>&1 | grep -E " error" ) &
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"; } > $OUT/machine.txt
(cd build-gpu && HORIZON_REQUIRE_GPU=1 timeout 240 ctest -j 8 -R "cuda|Cuda" > $OUT/gpu_tests.txt 2>&1)
grep -E "tests passed|tests failed|Total Test" $OUT/gpu_tests.txt; grep -E "\(Failed\)|Timeout" $OUT/gpu_tests.txt | head
wait
ARGS="--sizes ${SIZES:-100,200,400} --cloud-points 8000000 --reps 5 --cpu-max-n 0"
for round in 1 2; do for tree in new old; do
  bin=build-gpu/bin; [ $tree = old ] && bin=.deps/old-src/build-gpu/bin
  timeout 100 $bin/horizon_gpu_bench $ARGS > $OUT/${tree}_$round.csv 2> $OUT/${tree}_$round.err
done; done
python3 - $OUT <<'PY' | tee $OUT/summary.txt
import csv, sys, glob
for f in sorted(glob.glob(sys.argv[1] + '/*_[0-9].csv')):
    rows = list(csv.DictReader(l for l in open(f) if not l.startswith('#')))
    print(f.split('/')[-1])
    for r in rows:
        print(f"  {r['problem'][:4]}{r['n']}/{r['m']}: device {float(r['device_s'])*1e3:.2f} ms; host {float(r['host_s'])*1e3:.1f} ms = {r['host_vs_copy_floor']} x floor "
              f"(h2d {float(r['h2d_s'])*1e3:.1f}, grid {float(r['grid_s'])*1e3:.1f}, kernels {float(r['kernels_s'])*1e3:.1f}, d2h {float(r['d2h_s'])*1e3:.1f}); first {r['host_first_vs_copy_floor']}")
PY
