#!/usr/bin/python3
"""The multi-GPU study's JSON lines (run_multi_gpu.sh) as the thesis's Table 5.2, a CSV and plots.

Every run's neighbour count is checked against the closed-form lattice total first; a mismatch
stops the script with status 1. Times are host->host with partitioning, halo and assembly
included: one-process = the CLI's "search" seconds (partition + parts + assembly); mpi = its
preprocess + decompose + communicate + search. "resident" is the slowest GPU's device-resident
build (one-process runs). Usage: plot_multi_gpu.py RUNS.jsonl OUT_DIR
Writes OUT_DIR/multi_gpu.csv, OUT_DIR/table_5_2.md and speedup/phases figures (PNG + SVG)."""
import csv
import itertools
import json
import os
import statistics
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scaling"))
from plot_scaling import save  # noqa: E402  (PNG + SVG, as the CPU scaling study)


def lattice_entries(n, m):
    """Entries of the full list of the n^3 lattice at horizon m h (sum over offsets |v| < m)."""
    r = int(m)
    total = 0
    for v in itertools.product(range(-r, r + 1), repeat=3):
        if any(v) and sum(c * c for c in v) < m * m:
            total += (n - abs(v[0])) * (n - abs(v[1])) * (n - abs(v[2]))
    return total


def seconds(run):
    s = run["result"]["seconds"]
    if run["mode"] == "mpi":
        return s["preprocess"] + s["decompose"] + s["communicate"] + s["search"]
    return s["search"]


def phases(run):
    s = run["result"]["seconds"]
    if run["mode"] == "mpi":
        return {"partition": s["preprocess"] + s["decompose"], "halo": s["communicate"], "search": s["search"],
                "assemble": 0.0}
    parts = max((p["seconds"] for p in run["result"].get("gpus", [])), default=s["search"])
    return {"partition": s.get("partition", 0.0), "halo": 0.0, "search": parts, "assemble": s.get("assemble", 0.0)}


def resident(run):
    gpus = run["result"].get("gpus")
    if gpus:
        return max(p["build_seconds"] for p in gpus)
    return run["result"]["seconds"].get("kernels", float("nan"))


def load(path):
    runs = defaultdict(list)
    for line in open(path):
        if line.startswith("{"):
            r = json.loads(line)
            expected = lattice_entries(r["n"], r["m"])
            if r["result"]["neighbors"] != expected:
                sys.exit(f"{path}: {r['mode']} n={r['n']} m={r['m']} gpus={r['gpus']}: "
                         f"{r['result']['neighbors']} neighbours, closed form {expected}")
            runs[(r["n"], r["m"], r["mode"], r["gpus"])].append(r)
    rows = []
    for (n, m, mode, g), reps in sorted(runs.items()):
        ph = {k: statistics.median(phases(r)[k] for r in reps) for k in ("partition", "halo", "search", "assemble")}
        imbalance = reps[0]["result"].get("imbalance", {})
        rows.append(dict(n=n, m=m, points=n ** 3, mode=mode, gpus=g, seconds=statistics.median(map(seconds, reps)),
                         resident_s=statistics.median(map(resident, reps)),
                         **{f"{k}_s": v for k, v in ph.items()},
                         imbalance_points=imbalance.get("points", 1.0), imbalance_entries=imbalance.get("entries", 1.0),
                         neighbors=reps[0]["result"]["neighbors"]))
    # One GPU (one-process) is the base of both modes' speedups.
    base = {(r["n"], r["m"]): r["seconds"] for r in rows if r["gpus"] == 1 and r["mode"] == "one-process"}
    for r in rows:
        t1 = base.get((r["n"], r["m"]))
        r["speedup"] = t1 / r["seconds"] if t1 and r["seconds"] else float("nan")
        r["points_per_s"] = r["points"] / r["seconds"] if r["seconds"] else 0
    return rows


def main():
    runs, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    rows = load(runs)
    with open(os.path.join(out, "multi_gpu.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    counts = sorted({r["gpus"] for r in rows})
    with open(os.path.join(out, "table_5_2.md"), "w") as f:
        f.write("| n | points | m | " + " | ".join(f"{g} GPU{'s' if g > 1 else ''} ({mode}) s, speedup"
                                               for g in counts for mode in ("one-process", "mpi")
                                               if g > 1 or mode == "one-process") + " |\n")
        f.write("| --- " * (3 + sum(2 if g > 1 else 1 for g in counts)) + "|\n")
        for (n, m), group in itertools.groupby(sorted(rows, key=lambda r: (r["m"], r["n"])), lambda r: (r["n"], r["m"])):
            cells = {(r["mode"], r["gpus"]): r for r in group}
            line = [str(n), f"{n ** 3:,}", str(m)]
            for g in counts:
                for mode in ("one-process", "mpi"):
                    if g == 1 and mode == "mpi":
                        continue
                    r = cells.get((mode, g))
                    line.append(f"{r['seconds']:.3f}, {r['speedup']:.2f}×" if r else "–")
            f.write("| " + " | ".join(line) + " |\n")
    for m in sorted({r["m"] for r in rows}):
        fig, ax = plt.subplots(figsize=(6, 4))
        for mode, g in sorted({(r["mode"], r["gpus"]) for r in rows if r["gpus"] > 1}):
            sel = [r for r in rows if r["m"] == m and r["mode"] == mode and r["gpus"] == g]
            ax.plot([r["points"] for r in sel], [r["speedup"] for r in sel], "o-", label=f"{g} GPUs, {mode}")
        ax.set_xscale("log")
        ax.set_xlabel("points")
        ax.set_ylabel("speedup over one GPU (host→host)")
        ax.set_title(f"lattice, m = {m}")
        ax.grid(alpha=0.3)
        ax.legend()
        save(fig, out, f"multi_gpu_speedup_m{m}")
        fig, ax = plt.subplots(figsize=(7, 4))
        sel = [r for r in rows if r["m"] == m and r["n"] == max(x["n"] for x in rows)]
        labels = [f"{r['gpus']} {r['mode']}" for r in sel]
        bottom = [0.0] * len(sel)
        for phase in ("partition", "halo", "search", "assemble"):
            values = [r[f"{phase}_s"] for r in sel]
            ax.bar(labels, values, bottom=bottom, label=phase)
            bottom = [b + v for b, v in zip(bottom, values)]
        ax.set_ylabel("seconds")
        ax.set_title(f"phases, lattice n = {sel[0]['n'] if sel else '?'}, m = {m}")
        ax.legend()
        save(fig, out, f"multi_gpu_phases_m{m}")


if __name__ == "__main__":
    main()
