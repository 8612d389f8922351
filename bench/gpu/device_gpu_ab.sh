#!/usr/bin/env bash
# GPU A/B on the GPU machine: builds this tree and an older one (unpacked under .deps/old-src)
# with CUDA, runs the GPU suite (GPU required) on this one, horizon_gpu_bench of both
# alternately, then per-kernel durations (Nsight Compute) of both at lattice 200.
# Usage (repository root, old tree in .deps/old-src, carry [".deps"]):
#   [SIZES=100,200,400] [ROUNDS=2] bash bench/gpu/device_gpu_ab.sh  (writes under $OUT)
source bench/gpu/device_build.sh
source bench/gpu/device_build_old.sh horizon_gpu_bench
(cd build-gpu && HORIZON_REQUIRE_GPU=1 ctest -j 16 -R "cuda|Cuda" > "$OUT/gpu_tests.txt" 2>&1)
grep -E "tests passed|tests failed" "$OUT/gpu_tests.txt"; grep -E "\(Failed\)" "$OUT/gpu_tests.txt" | head
ARGS="--sizes ${SIZES:-100,200,400} --cloud-points 8000000 --reps 3 ${BENCH_ARGS:-}"
for round in $(seq ${ROUNDS:-2}); do
  for tree in new old; do
    bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
    $bin/horizon_gpu_bench $ARGS > $OUT/${tree}_$round.csv 2> $OUT/${tree}_$round.err
  done
done
for tree in new old; do
  bin=build-gpu/bin; [ $tree = old ] && bin=$OLD/bin
  ncu --clock-control none --metrics gpu__time_duration.sum,smsp__inst_executed.sum --csv \
    $bin/horizon_gpu_bench --sizes 200 --cloud-points 0 --reps 1 --no-host > $OUT/ncu_$tree.csv 2> /dev/null
done
python3 - $OUT <<'PY' | tee $OUT/summary.txt
import csv, sys, glob, collections
out = sys.argv[1]
for f in sorted(glob.glob(out + '/*_[0-9].csv')):
    rows = [r for r in csv.DictReader(l for l in open(f) if not l.startswith('#'))]
    print(f.split('/')[-1], ' '.join(f"{r['problem'][:4]}{r['n']}/{r['m']}:{float(r['device_s'])*1e3:.2f}ms,{r['device_vs_naive']}x" for r in rows))
for tree in ('new', 'old'):
    rows = [r for r in csv.reader(l for l in open(f'{out}/ncu_{tree}.csv') if l.startswith('"'))][1:]
    agg = collections.OrderedDict()
    for r in rows:
        name = r[4].split('(')[0][-40:]; key = (name, r[12])
        agg.setdefault(key, []).append(float(r[-1].replace(',', '')))
    for (name, metric), v in agg.items():
        if 'families' in name or 'short_rows' in name or 'gather' in name:
            print(tree, f"{name:40s} {metric:28s}", ' '.join(f"{x/1e6:.3f}" if 'time' in metric else f"{x:.3g}" for x in v))
PY
