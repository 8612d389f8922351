"""Points that live on the GPU as a PyTorch tensor: searched where they lie, the list left there;
then atoms in a periodic hexagonal cell, their distances and vectors left on the GPU too.
Prints a line and exits 0 where there is no GPU or no PyTorch."""
import numpy as np

import horizon

try:
    import torch
except ImportError:
    torch = None

if torch is None or not horizon.backend_available("cuda"):
    print("no GPU or no PyTorch: nothing to show")
else:
    points = torch.from_numpy(horizon.lattice(50)).cuda()  # (125000, 3) float64 on the GPU
    nl = horizon.search(points, 3.015 * 10 / 50)            # a DeviceNeighborList, on the GPU
    indices = torch.as_tensor(nl.indices, device="cuda")    # no copy (__cuda_array_interface__)
    offsets = torch.as_tensor(nl.offsets, device="cuda")
    family_sizes = offsets[1:] - offsets[:-1]
    print(f"{nl.total} entries; largest family {int(family_sizes.max())}")
    assert nl.total == horizon.search(points.cpu().numpy(), 3.015 * 10 / 50).total

    # Atoms in a hexagonal cell (rows: the cell vectors), periodic on every axis, a 5 A cutoff.
    cell = np.array([[20.0, 0, 0], [-10.0, 10.0 * 3**0.5, 0], [0, 0, 20.0]])
    fractions = torch.rand(800, 3, dtype=torch.float64, device="cuda", generator=torch.Generator("cuda").manual_seed(1))
    atoms = fractions @ torch.from_numpy(cell).cuda()
    nl = horizon.search(atoms, 5.0, cell=cell, shifts=True, distances=True, vectors=True)
    d = torch.as_tensor(nl.distances, device="cuda")        # (total,) on the GPU
    D = torch.as_tensor(nl.vectors, device="cuda")          # (total, 3): x_j + S . cell - x_i
    assert torch.allclose(d, D.norm(dim=1))
    on_host = horizon.search(atoms.cpu().numpy(), 5.0, cell=cell, shifts=True)
    assert np.array_equal(torch.as_tensor(nl.shifts, device="cuda").cpu().numpy(), on_host.shifts)
    print(f"{nl.total} pairs within 5 A; mean distance {float(d.mean()):.3f} A")
