#!/usr/bin/python3
"""horizon_parts_bench's CSV as the predicted Table 5.2: a markdown table and the predicted
speed-up against the GPU count, beside the thesis's two K40s (Table 5.2: "going from one to two
GPUs perfectly doubles the obtained throughput"). Every row's entry count is checked against the
closed-form lattice total first (exit 1 on a mismatch).
Usage: plot_parts.py PARTS.csv OUT_DIR   (writes OUT_DIR/parts_prediction.md and parts_speedup.png/.svg)"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scaling"))
from plot_scaling import save  # noqa: E402
from plot_multi_gpu import lattice_entries  # noqa: E402

THESIS_TWO_K40 = 2.0  # Table 5.2, Fig. 5.3/5.4: two GPUs halve the run time


def main():
    path, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    rows = [r for r in csv.DictReader(line for line in open(path) if not line.startswith("#"))]
    for r in rows:
        n, m = int(r["n"]), float(r["m"])
        if int(r["entries"]) != lattice_entries(n, m):
            sys.exit(f"{path}: n={n} m={m}: {r['entries']} entries, closed form {lattice_entries(n, m)}")
    with open(os.path.join(out, "parts_prediction.md"), "w") as f:
        f.write("| n | m | GPUs | halo | predicted, device-resident | predicted, host→host | "
                "parts on one GPU / (one part × (1 + halo)), resident | same, host→host |\n")
        f.write("| --- " * 8 + "|\n")
        for r in rows:
            f.write(f"| {r['n']} | {r['m']} | {r['parts']} | {100 * float(r['halo_share']):.1f} % | "
                    f"{float(r['predicted_speedup_resident']):.2f}× | {float(r['predicted_speedup_host']):.2f}× | "
                    f"{float(r['parts_call_resident_ratio']):.2f} | {float(r['parts_call_host_ratio']):.2f} |\n")
    fig, ax = plt.subplots(figsize=(6, 4))
    counts = sorted({int(r["parts"]) for r in rows})
    ax.plot(counts, counts, ":", color="grey", label="ideal")
    for key in sorted({(int(r["n"]), float(r["m"])) for r in rows}):
        sel = [r for r in rows if (int(r["n"]), float(r["m"])) == key]
        ax.plot([int(r["parts"]) for r in sel], [float(r["predicted_speedup_resident"]) for r in sel], "o-",
                label=f"n = {key[0]}, m = {key[1]}, resident")
    ax.plot([2], [THESIS_TWO_K40], "k*", markersize=12, label="thesis, 2 K40 (Table 5.2)")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log", base=2)
    ax.set_xlabel("GPUs")
    ax.set_ylabel("speed-up over one GPU (predicted)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, out, "parts_speedup")


if __name__ == "__main__":
    main()
