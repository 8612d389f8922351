"""The README's CPU table from two horizon_bench CSVs (the 2-core VM and the 16-core host).

Usage: /usr/bin/python3 bench/cpu/readme_table.py VM.csv HOST.csv
Points/s in millions (grid + search); ratios against the textbook list at the same thread count.
"""
import csv
import sys


def load(path):
    rows = [r for r in csv.DictReader(line for line in open(path) if not line.startswith("#"))]
    return {(r["problem"], r["m"], r["impl"], r["rows"], int(r["threads"])): r for r in rows}


def rate(table, problem, m, impl, rows, threads):
    return float(table[(problem, m, impl, rows, threads)]["points_per_s"]) / 1e6


vm, host = load(sys.argv[1]), load(sys.argv[2])
host_threads = max(k[4] for k in host)
vm_threads = max(k[4] for k in vm)
names = {"lattice": "lattice", "lattice-shuffled": "lattice, random order", "random": "random cloud",
         "clustered": "64 Gaussian clusters"}
print("| problem | m | VM: textbook 1 core | VM: serial | ratio | VM: openmp 2 / textbook 2 | host: textbook 1 core "
      "| host: serial | ratio | host: textbook 16 threads | host: openmp 16 | ratio | host: openmp / serial |")
print("| --- " * 13 + "|")
for problem in names:
    for m in ("1.5", "3.015"):
        t1, s1 = rate(vm, problem, m, "textbook", "unsorted", 1), rate(vm, problem, m, "serial", "sorted", 1)
        t2, o2 = rate(vm, problem, m, "textbook", "unsorted", vm_threads), rate(vm, problem, m, "openmp", "sorted", vm_threads)
        h1, hs = rate(host, problem, m, "textbook", "unsorted", 1), rate(host, problem, m, "serial", "sorted", 1)
        ht, ho = (rate(host, problem, m, "textbook", "unsorted", host_threads),
                  rate(host, problem, m, "openmp", "sorted", host_threads))
        print(f"| {names[problem]} | {m} | {t1:.2f} | {s1:.2f} | {s1 / t1:.2f}× | {o2 / t2:.2f}× | {h1:.2f} | {hs:.2f} "
              f"| {hs / h1:.2f}× | {ht:.2f} | {ho:.2f} | {ho / ht:.2f}× | {ho / hs:.1f}× |")
