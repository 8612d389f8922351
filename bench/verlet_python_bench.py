"""horizon.VerletList.refresh against a fresh horizon.search of the same moved points (skin 0.1 h,
moves up to skin/5 per axis), lists checked equal. Run: PYTHONPATH=build/python python3 bench/verlet_python_bench.py"""
import time, sys, numpy as np
import horizon
pts = horizon.lattice(100); h = 0.15; skin = 0.1 * h
rng = np.random.default_rng(1)
t = time.perf_counter(); v = horizon.VerletList(pts, h, skin, backend="openmp"); build = time.perf_counter() - t
moved = pts + rng.uniform(-skin / 5, skin / 5, pts.shape)
assert not v.needs_rebuild(moved)
def best(f, reps=3):
    out = []
    for _ in range(reps):
        t = time.perf_counter(); r = f(); out.append(time.perf_counter() - t)
    return min(out), r
tr, a = best(lambda: v.refresh(moved))
ts, b = best(lambda: horizon.search(moved, h, backend="openmp"))
tn, _ = best(lambda: v.needs_rebuild(moved))
assert np.array_equal(a.offsets, b.offsets) and np.array_equal(a.indices, b.indices)
print(f"lattice 100 (1e6 points), h=0.15 (m=1.5), skin=0.1h, openmp 2 threads: build {build:.3f} s, "
      f"refresh {tr:.3f} s, fresh search {ts:.3f} s, search/refresh {ts/tr:.2f}x, needs_rebuild {tn:.3f} s; lists equal")
