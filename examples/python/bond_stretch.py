"""A peridynamic bond-stretch loop over horizon's list, in NumPy (bond-based, prototype
microelastic material): each point's family from horizon.search, the bonds' stretch under a
uniform extension, and the force density on each point from its bonds.

    python3 examples/bond_stretch.py [n]
"""
import sys

import numpy as np

import horizon

n = int(sys.argv[1]) if len(sys.argv) > 1 else 40
points = horizon.lattice(n)                  # n^3 points in a 10 x 10 x 10 block
spacing = 10.0 / n
delta = 3.015 * spacing                      # the horizon: m = 3.015 lattice spacings
nl = horizon.search(points, delta, half=True)  # each bond once
i = np.repeat(np.arange(len(nl)), np.diff(nl.offsets))
j = nl.indices.astype(np.int64)

# Reference bond vectors and lengths, then a 1 % extension along x.
xi = points[j] - points[i]
length = np.linalg.norm(xi, axis=1)
displaced = points * np.array([1.01, 1.0, 1.0])
eta = displaced[j] - displaced[i]
deformed = np.linalg.norm(eta, axis=1)
stretch = (deformed - length) / length

# Pairwise force density c * s * e (unit direction of the deformed bond), equal and opposite.
bulk_modulus = 1.0
c = 18.0 * bulk_modulus / (np.pi * delta**4)
volume = spacing**3
f = (c * stretch * volume)[:, None] * eta / deformed[:, None]
force = np.zeros_like(points)
np.add.at(force, i, f)
np.add.at(force, j, -f)

print(f"{len(points)} points, {len(i)} bonds ({nl.total / len(points) * 2:.1f} per point), horizon {delta:.4f}")
print(f"stretch: mean {stretch.mean():.5f}, max {stretch.max():.5f}")
interior = np.all((points > delta) & (points < 10 - delta), axis=1)
print(f"net force on interior points (should vanish): {np.abs(force[interior]).max():.3e}")
print(f"largest force at the x faces: {np.abs(force[:, 0]).max():.3e}")
