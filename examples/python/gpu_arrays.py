"""Points that live on the GPU as a PyTorch tensor: searched where they lie, the list left there.
Prints a line and exits 0 where there is no GPU or no PyTorch."""
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
