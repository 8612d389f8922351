"""The pictures to look at first: the family-size histogram, and a slice of the cloud coloured
by family size (surfaces and sparse regions have smaller families). Writes PNGs.

    python3 examples/family_sizes.py [out_prefix]
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import horizon

prefix = sys.argv[1] if len(sys.argv) > 1 else "family_sizes"
points = horizon.clustered_cloud(200000, clusters=12, sigma=1.2, seed=4)
nl = horizon.search(points, 0.25)
sizes = np.diff(nl.offsets)

fig, ax = plt.subplots(figsize=(6, 4))
ax.hist(sizes, bins=60, color="#3070b0")
ax.set_xlabel("family size (neighbours within the horizon)")
ax.set_ylabel("points")
ax.set_title(f"{len(points)} points, horizon 0.25: mean {sizes.mean():.1f}, max {sizes.max()}")
fig.tight_layout()
fig.savefig(prefix + "_histogram.png", dpi=120)

middle = np.abs(points[:, 2] - np.median(points[:, 2])) < 0.2
fig, ax = plt.subplots(figsize=(6, 5.5))
shown = ax.scatter(points[middle, 0], points[middle, 1], c=sizes[middle], s=2, cmap="viridis")
fig.colorbar(shown, ax=ax, label="family size")
ax.set_aspect("equal")
ax.set_title("slice |z - median| < 0.2, coloured by family size")
fig.tight_layout()
fig.savefig(prefix + "_slice.png", dpi=120)
print(f"wrote {prefix}_histogram.png and {prefix}_slice.png")
