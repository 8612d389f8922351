#!/usr/bin/env bash
# One device call: where do the host path's slow uploads come from (h2d 95 and 156 ms against
# 5.5 and 35 ms, in 2 of 30 problem runs with page-locked list blocks, none in 20 without)?
# Processes of horizon_gpu_bench (RUNS, default "1 2 3"), every host call's phases on stderr, and the kernel's
# THP and compaction counters around each.
# Usage (device, carry [".deps"]): bash bench/results/pinned_lists_1206/upload_outliers.sh
CMAKE_ARGS="-DHORIZON_PYTHON=off -DHORIZON_MPI=OFF" source bench/gpu/device_build.sh
{ nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"; cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag; } > $OUT/machine.txt
for run in ${RUNS:-1 2 3}; do
  echo "before $run: $(grep -E '^(thp_fault_alloc|thp_fault_fallback|compact_stall|compact_fail|thp_collapse_alloc) ' /proc/vmstat | tr '\n' ' ')" >> $OUT/vmstat.txt
  timeout 150 $BUILD/bin/horizon_gpu_bench --sizes 200,400 --cloud-points 0 --reps 5 --cpu-max-n 0 > $OUT/run_$run.csv 2> $OUT/run_$run.err
done
echo "after: $(grep -E '^(thp_fault_alloc|thp_fault_fallback|compact_stall|compact_fail|thp_collapse_alloc) ' /proc/vmstat | tr '\n' ' ')" >> $OUT/vmstat.txt
python3 - $OUT <<'PY2'  # the calls whose upload took over twice the problem's fastest
import glob, re, sys, collections
calls = collections.defaultdict(list)
for f in sorted(glob.glob(sys.argv[1] + '/run_*.err')):
    for line in open(f):
        if m := re.match(r'host (\S+ \d+ m=\S+) call (\d+): (\S+) ms \(h2d (\S+),', line):
            calls[m[1]].append((f[-5], int(m[2]), float(m[3]), float(m[4])))
for problem, c in calls.items():
    fastest = min(h for *_, h in c)
    slow = [f"run {r} call {k}: {t} ms, h2d {h}" for r, k, t, h in c if h > 2 * fastest]
    print(f"{problem}: fastest h2d {fastest} ms; {len(slow)} of {len(c)} calls slower than twice that", *slow, sep="\n  ")
PY2
