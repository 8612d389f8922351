#!/usr/bin/env bash
# Device call of 2026-12-06 (results beside it, README.md): this tree (the page-locked list blocks registered in pieces of
# 256 MB or more, one thread each: src/backends/cuda/pinned_blocks.cuh) against .deps/old-src
# (main, one cudaHostRegister per block). Answers two questions in one call:
#  - does registering in parallel cut the second call's price (about twice a repeated call on
#    the H100 host: lattice 400 at m = 3.015 1.7-3.3 s against 0.68 s; bench/results/pinned_lists_1206)?
#  - where do the slow uploads come from (h2d 95 and 156 ms against 5.5 and 35 ms, 2 of 30
#    problem runs with page-locked blocks)? Every host call's phases, per tree, and the kernel's
#    THP and compaction counters before and after.
# Usage: on main, `git apply bench/results/parallel_register_1206/parallel_register.patch` (the change,
# kept off main until it runs on a GPU), `.deps/old-src` = main unpacked; then on the device (carry [".deps"]):
#   bash bench/results/parallel_register_1206/run_on_device.sh
grep -E '^(thp_fault_alloc|thp_fault_fallback|compact_stall|compact_fail|thp_migration_success|pgmigrate_success) ' /proc/vmstat > /tmp/vmstat_before
ROUNDS=${ROUNDS:-2} SIZES=${SIZES:-200,400} CLOUD=0 TESTS="cuda|Cuda|Buffer" source bench/gpu/device_host_path_ab.sh
{ echo "# before"; cat /tmp/vmstat_before; echo "# after"
  grep -E '^(thp_fault_alloc|thp_fault_fallback|compact_stall|compact_fail|thp_migration_success|pgmigrate_success) ' /proc/vmstat; } >> $OUT/machine.txt
python3 - $OUT <<'PY' | tee -a $OUT/summary.txt  # per tree: the calls whose upload took over twice the fastest
import collections, re, sys
calls = collections.defaultdict(list)
for line in open(sys.argv[1] + '/errors.txt'):
    if m := re.match(r'(\w+)_(\d): host (\S+ \d+ m=\S+) call (\d+): (\S+) ms \(h2d (\S+),', line):
        calls[m[3]].append((m[1], m[2], int(m[4]), float(m[5]), float(m[6])))
for problem, c in calls.items():
    fastest = min(h for *_, h in c)
    print(f"{problem}: fastest upload {fastest} ms")
    for tree, rnd, call, total, h2d in c:
        if h2d > 2 * fastest or call == 1:
            print(f"  {tree} round {rnd} call {call}: {total} ms, h2d {h2d}" + (" (second call)" if call == 1 else ""))
PY
