#!/usr/bin/env bash
# The last, shorter call of run_on_device.sh (little device time was left): this tree only,
# the CLI and the tests, the partitioned tests with the GPU required, then lattice 400 host->host
# on one GPU and as two parts on it. Usage (device, .deps carried):
#   bash bench/results/gpu_parts_on_device_1205/run_new_only.sh
mkdir -p /opt/deps && for deb in .deps/*.deb; do dpkg -x "$deb" /opt/deps; done
export LD_LIBRARY_PATH=/opt/deps/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release -DHORIZON_CUDA=on -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF \
  -DCMAKE_PREFIX_PATH=/opt/deps/usr -DCMAKE_CUDA_ARCHITECTURES=90 > $OUT/configure.log 2>&1
cmake --build build-gpu -j "$(nproc)" --target horizon_cli horizon_tests 2>&1 | grep -E "error"
HORIZON_REQUIRE_GPU=1 build-gpu/bin/horizon_tests --gtest_filter='Partitioned*' > $OUT/tests.txt 2>&1
grep -E "PASSED|FAILED" $OUT/tests.txt | head
nvidia-smi -L > $OUT/gpu.txt
for m in 1.5 3.015; do for mode in "--device 0" "--gpus 0,0" "--gpus 0,0"; do
  build-gpu/bin/horizon search lattice:400 --horizon $(python3 -c "print($m / 40)") --backend cuda $mode --json --quiet |
    python3 -c "
import json, sys; d = json.load(sys.stdin); s = d['seconds']
parts = ' '.join('%.3f' % g['seconds'] for g in d.get('gpus', []))
print('new n=400 m=$m $mode entries %d total %.3f partition %s assemble %s parts [%s]' % (d['neighbors'],
      s.get('search', 0) + s.get('grid', 0), s.get('partition'), s.get('assemble'), parts))"
done; done 2>&1 | tee $OUT/cli.txt
