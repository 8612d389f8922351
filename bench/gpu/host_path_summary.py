"""Prints the host->host figures of every horizon_gpu_bench CSV named TREE_ROUND.csv in a folder
(the A/B calls' outputs): time, ratio to the PCIe copy floor, phases, first and second call.
Usage: python3 bench/gpu/host_path_summary.py FOLDER"""
import csv
import glob
import sys

for f in sorted(glob.glob(sys.argv[1] + '/*_[0-9].csv')):
    rows = list(csv.DictReader(l for l in open(f) if not l.startswith('#')))
    print(f.split('/')[-1])
    for r in rows:
        ms = lambda key: float(r[key]) * 1e3
        print(f"  {r['problem'][:4]}{r['n']}/{r['m']}: host {ms('host_s'):.1f} ms = {r['host_vs_copy_floor']} x floor "
              f"(h2d {ms('h2d_s'):.1f}, grid {ms('grid_s'):.1f}, kernels {ms('kernels_s'):.1f}, d2h {ms('d2h_s'):.1f}); "
              f"first {r['host_first_vs_copy_floor']}"
              + (f", second {ms('host_second_s'):.1f} ms" if r.get('host_second_s') else ""))
