#!/usr/bin/python3
"""Turns the scaling study's JSON lines into CSV and the thesis-style plots (Fig. 4.5-4.11).

Usage: plot_scaling.py RUNS.jsonl OUT_DIR [COMM_MODEL.csv]
Writes OUT_DIR/scaling.csv, and PNG + SVG figures."""
import csv
import json
import os
import statistics
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PHASES = ["preprocess", "decompose", "communicate", "search"]
STRATEGIES = ["thesis", "halo", "overlap"]


def load(path):
    runs = defaultdict(list)
    for line in open(path):
        line = line.strip()
        if not line.startswith("{"):
            continue
        r = json.loads(line)
        runs[(r["study"], r["n"], r["m"], r["ranks"], r["exchange"])].append(r)
    rows = []
    for (study, n, m, p, x), reps in sorted(runs.items()):
        def med(key):
            return statistics.median(r["seconds"][key] for r in reps)
        phases = {k: med(k) for k in PHASES}
        total = sum(phases.values())
        rows.append(dict(study=study, n=n, m=m, points=reps[0]["points"], ranks=p, exchange=x, total_s=total,
                         **{f"{k}_s": v for k, v in phases.items()},
                         bytes_sent=reps[0]["bytes_sent"], messages_sent=reps[0]["messages_sent"],
                         points_per_s=reps[0]["points"] / total if total else 0))
    # One-rank times: per problem for strong scaling, per study for weak scaling (n grows with p).
    def key(r):
        return (r["study"], r["n"] if r["study"] == "strong" else 0, r["m"], r["exchange"])
    base = {key(r): r["total_s"] for r in rows if r["ranks"] == 1}
    for r in rows:
        t1 = base.get(key(r))
        if r["study"] == "strong":
            r["speedup"] = t1 / r["total_s"] if t1 else 0
            r["efficiency"] = r["speedup"] / r["ranks"]
        else:  # weak: the work per rank is constant
            r["speedup"] = r["ranks"] * t1 / r["total_s"] if t1 else 0
            r["efficiency"] = t1 / r["total_s"] if t1 else 0
        r["communicate_share"] = r["communicate_s"] / r["total_s"] if r["total_s"] else 0
    return rows


def save(fig, out, name):
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, f"{name}.{ext}"), dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot(rows, out, m):
    strong = [r for r in rows if r["study"] == "strong" and r["m"] == m]
    sizes = sorted({r["n"] for r in strong})
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.5))
    for ax, x in zip(axes, STRATEGIES):  # Fig. 4.5: run time against cores, one line per size
        for n in sizes:
            pts = sorted((r["ranks"], r["total_s"]) for r in strong if r["n"] == n and r["exchange"] == x)
            ax.plot(*zip(*pts), marker="o", label=f"{n**3:,} points")
        ax.set(xscale="log", yscale="log", xlabel="ranks (cores)", ylabel="seconds", title=f"{x}: run time, m={m}")
        ax.legend(fontsize=7)
    save(fig, out, f"runtime_m{m}")

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))  # Fig. 4.7-4.8: efficiency and speedup
    largest = max(sizes)
    for x in STRATEGIES:
        pts = sorted((r["ranks"], r["speedup"], r["efficiency"]) for r in strong if r["n"] == largest and r["exchange"] == x)
        p, s, e = zip(*pts)
        axes[0].plot(p, s, marker="o", label=x)
        axes[1].plot(p, e, marker="o", label=x)
    axes[0].plot(p, p, "k--", label="ideal")
    axes[0].set(xlabel="ranks", ylabel="speedup", title=f"speedup, {largest**3:,} points, m={m}")
    axes[1].set(xlabel="ranks", ylabel="efficiency", title=f"efficiency, {largest**3:,} points, m={m}", ylim=(0, 1.1))
    for ax in axes:
        ax.legend()
    save(fig, out, f"speedup_m{m}")

    fig, axes = plt.subplots(1, 3, figsize=(16, 4.5), sharey=True)  # Fig. 4.10: share of each phase
    for ax, x in zip(axes, STRATEGIES):
        sel = sorted((r for r in strong if r["n"] == largest and r["exchange"] == x), key=lambda r: r["ranks"])
        bottom = [0.0] * len(sel)
        for phase in PHASES:
            share = [100 * r[f"{phase}_s"] / r["total_s"] for r in sel]
            ax.bar([str(r["ranks"]) for r in sel], share, bottom=bottom, label=phase)
            bottom = [b + s for b, s in zip(bottom, share)]
        ax.set(xlabel="ranks", title=f"{x}: % of time per phase, {largest**3:,} points")
    axes[0].set_ylabel("% of run time")
    axes[0].legend()
    save(fig, out, f"phases_m{m}")

    fig, axes = plt.subplots(1, 3, figsize=(16, 4.5))  # Fig. 4.11: iso-efficiency contours
    for ax, x in zip(axes, STRATEGIES):
        sel = [r for r in strong if r["exchange"] == x and r["ranks"] > 1]
        if len({r["ranks"] for r in sel}) > 1:
            cs = ax.tricontour([r["ranks"] for r in sel], [r["points"] for r in sel], [r["efficiency"] for r in sel],
                               levels=[0.2, 0.4, 0.6, 0.8, 0.9])
            ax.clabel(cs, fontsize=8)
        ax.set(xscale="log", xlabel="ranks", ylabel="points", title=f"{x}: iso-efficiency, m={m}")
    save(fig, out, f"isoefficiency_m{m}")


def plot_model(path, out):
    rows = list(csv.DictReader(open(path)))
    for m in sorted({r["m"] for r in rows}):
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        for s in ["thesis", "halo_brick", "halo_rcb"]:
            sel = sorted((int(r["ranks"]), float(r["max_rank_bytes"]), int(r["max_rank_messages"]))
                         for r in rows if r["m"] == m and r["strategy"] == s and int(r["ranks"]) > 1)
            if sel:
                p, b, msg = zip(*sel)
                axes[0].plot(p, b, marker="o", label=s)
                axes[1].plot(p, msg, marker="o", label=s)
        axes[0].set(xscale="log", yscale="log", xlabel="ranks", ylabel="bytes sent by the busiest rank",
                    title=f"ghost volume, lattice n={rows[0]['n']}, m={m}")
        axes[1].set(xscale="log", yscale="log", xlabel="ranks", ylabel="messages sent by the busiest rank",
                    title="messages")
        for ax in axes:
            ax.legend()
        save(fig, out, f"comm_model_m{m}")


def main():
    runs, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    rows = load(runs)
    with open(os.path.join(out, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    for m in sorted({r["m"] for r in rows}):
        plot(rows, out, m)
    if len(sys.argv) > 3:
        plot_model(sys.argv[3], out)


if __name__ == "__main__":
    main()
