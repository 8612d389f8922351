"""Draws docs/images/throughput.png and prints the same-run ratio tables of the README and the
Performance page, from the committed CSVs in bench/results/ (nothing is typed in by hand).

Run from the repository root: python3 bench/plots/docs_figures.py
"""
import csv
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

RESULTS = pathlib.Path("bench/results")
CPU_RUNS = {"2-core AMD Zen 5 VM": RESULTS / "vm_2core_zen5" / "cpu_bench.csv",
            "16-core Intel Xeon (H100 host)": RESULTS / "h100_host_16core" / "cpu_bench.csv"}
GPU_RUN = RESULTS / "h100" / "gpu_bench.csv"
CPU_PROBLEMS = [("lattice", "lattice"), ("lattice-shuffled", "lattice, random order"),
                ("random", "random cloud"), ("clustered", "64 clusters")]


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def cpu_rate(table, problem, m, impl, threads_max):
    """points/s of `impl` (sorted rows for horizon) at one thread or at the run's most threads."""
    found = [r for r in table if r["problem"] == problem and r["m"] == m and r["impl"] == impl
             and r["rows"] in ("sorted", "unsorted" if impl == "textbook" else "sorted")]
    threads = max(int(r["threads"]) for r in found) if threads_max else 1
    return next(float(r["points_per_s"]) for r in found if int(r["threads"]) == threads), threads


def cpu_series(path):
    table = rows(path)
    series = {"textbook cell list, 1 core": [], "horizon serial": [], "textbook cell list, all cores": [],
              "horizon openmp, all cores": []}
    labels = []
    for problem, label in CPU_PROBLEMS:
        for m in ("1.5", "3.015"):
            labels.append(f"{label}\nm = {m}")
            series["textbook cell list, 1 core"].append(cpu_rate(table, problem, m, "textbook", False)[0])
            series["horizon serial"].append(cpu_rate(table, problem, m, "serial", False)[0])
            series["textbook cell list, all cores"].append(cpu_rate(table, problem, m, "textbook", True)[0])
            series["horizon openmp, all cores"].append(cpu_rate(table, problem, m, "openmp", True)[0])
    return labels, series


def gpu_series():
    table = rows(GPU_RUN)
    labels, series = [], {"naive GPU cell list (device)": [], "horizon, device-resident": [],
                          "horizon, host to host": []}
    for r in table:
        name = f"lattice {r['n']}" if r["problem"] == "lattice" else f"{r['problem']} 8M"
        labels.append(f"{name}\nm = {r['m']}")
        series["naive GPU cell list (device)"].append(float(r["naive_points_per_s"]))
        series["horizon, device-resident"].append(float(r["device_points_per_s"]))
        series["horizon, host to host"].append(float(r["host_points_per_s"]))
    return labels, series


def bars(axis, labels, series, title, colors):
    width = 0.8 / len(series)
    for k, (name, values) in enumerate(series.items()):
        axis.bar([i + (k - (len(series) - 1) / 2) * width for i in range(len(labels))], values, width,
                 label=name, color=colors[k])
    axis.set_yscale("log")
    axis.set_xticks(range(len(labels)), labels, fontsize=7)
    axis.set_ylabel("points / s (grid + search)")
    axis.set_title(title, fontsize=10)
    axis.legend(fontsize=7, loc="upper right")
    axis.grid(axis="y", alpha=0.3)


def main():
    figure, axes = plt.subplots(3, 1, figsize=(11, 12))
    cpu_colors = ["#bbbbbb", "#1f77b4", "#777777", "#ff7f0e"]
    for axis, (machine, path) in zip(axes, CPU_RUNS.items()):
        labels, series = cpu_series(path)
        bars(axis, labels, series, f"CPU: {machine}, 10^6 points, sorted rows (textbook rows unsorted)", cpu_colors)
    labels, series = gpu_series()
    bars(axes[2], labels, series, "GPU: NVIDIA H100, sorted rows (naive rows unsorted)", ["#bbbbbb", "#2ca02c", "#98df8a"])
    figure.suptitle("horizon against anchors run in the same process on the same points", fontsize=12)
    figure.tight_layout()
    out = pathlib.Path("docs/images/throughput.png")
    figure.savefig(out, dpi=110)
    print(f"wrote {out}")

    # The ratio tables (same run, same points).
    print("\n| problem | m | VM serial ÷ textbook | VM openmp ÷ textbook (2 cores) | Xeon serial ÷ textbook | Xeon openmp ÷ textbook (16 cores) |")
    print("| --- | --- | --- | --- | --- | --- |")
    tables = {name: rows(path) for name, path in CPU_RUNS.items()}
    vm, host = tables.values()
    for problem, label in CPU_PROBLEMS:
        for m in ("1.5", "3.015"):
            cells = []
            for table in (vm, host):
                for threads_max, impl in ((False, "serial"), (True, "openmp")):
                    ours = cpu_rate(table, problem, m, impl, threads_max)[0]
                    anchor = cpu_rate(table, problem, m, "textbook", threads_max)[0]
                    cells.append(f"{ours / 1e6:.2f} M/s ({ours / anchor:.2f}×)")
            print(f"| {label} | {m} | " + " | ".join(cells) + " |")
    print("\n| problem | m | device-resident | ÷ naive | host to host | GPU ÷ 16-core openmp |")
    print("| --- | --- | --- | --- | --- | --- |")
    for r in rows(GPU_RUN):
        name = f"lattice {r['n']}" if r["problem"] == "lattice" else f"{r['problem']} 8 M"
        print(f"| {name} | {r['m']} | {float(r['device_points_per_s']):.2e} | {float(r['device_vs_naive']):.2f}× | "
              f"{float(r['host_points_per_s']):.2e} | {float(r['gpu_vs_openmp']):.1f}× |")


if __name__ == "__main__":
    main()
