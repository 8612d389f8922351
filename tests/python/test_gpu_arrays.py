"""CUDA arrays in (PyTorch, CuPy: __cuda_array_interface__), a DeviceNeighborList out whose arrays
those libraries take without a copy. Skips without a GPU or without either library."""
import numpy as np
import pytest

import horizon

if not horizon.backend_available("cuda"):
    pytest.skip("no usable GPU", allow_module_level=True)

libraries = []
try:
    import torch

    libraries.append("torch")
except ImportError:
    pass
try:
    import cupy

    libraries.append("cupy")
except ImportError:
    pass


def to_gpu(library, array):
    return torch.from_numpy(array).cuda() if library == "torch" else cupy.asarray(array)


def to_numpy(library, cuda_array):
    if library == "torch":
        return torch.as_tensor(cuda_array, device="cuda").cpu().numpy()
    return cupy.asnumpy(cupy.asarray(cuda_array))


@pytest.mark.parametrize("library", libraries)
@pytest.mark.parametrize("dims,h", [(3, 0.5), (3, 1.0), (2, 0.1)])
@pytest.mark.parametrize("half", [False, True])
def test_device_list_equals_host_list(library, dims, h, half):
    points = horizon.random_cloud(50000, dims=dims, seed=11)
    reference = horizon.search(points, h, half=half, backend="serial")
    nl = horizon.search(to_gpu(library, points), h, half=half)
    assert isinstance(nl, horizon.DeviceNeighborList) and len(nl) == len(points) and nl.total == reference.total
    np.testing.assert_array_equal(to_numpy(library, nl.offsets), reference.offsets)
    np.testing.assert_array_equal(to_numpy(library, nl.indices), reference.indices)
    host = nl.to_host()
    np.testing.assert_array_equal(host.indices, reference.indices)


@pytest.mark.parametrize("library", libraries)
def test_arrays_outlive_the_list_object(library):
    points = horizon.lattice(30)
    nl = horizon.search(to_gpu(library, points), 0.5)
    indices = torch.as_tensor(nl.indices, device="cuda") if library == "torch" else cupy.asarray(nl.indices)
    del nl
    assert int(indices.sum()) == int(horizon.search(points, 0.5).indices.sum())


@pytest.mark.parametrize("library", libraries)
def test_clear_errors_for_gpu_arrays(library):
    points = to_gpu(library, horizon.random_cloud(100, seed=1))
    with pytest.raises(ValueError, match="float64"):
        horizon.search(points.float() if library == "torch" else points.astype(cupy.float32), 0.5)
    wide = to_gpu(library, np.zeros((100, 4)))
    with pytest.raises(ValueError, match="C-contiguous"):
        horizon.search(wide[:, :3], 0.5)


@pytest.mark.parametrize("library", libraries)
@pytest.mark.parametrize("half", [False, True])
def test_a_cell_on_the_gpu_gives_the_hosts_entries_and_geometry(library, half):
    rng = np.random.default_rng(58)
    cell = np.array([[6.0, 0, 0], [2.0, 5.5, 0], [-1.0, 1.5, 7.0]])
    points = rng.uniform(-0.5, 1.5, (3000, 3)) @ cell  # atoms inside and outside the cell
    kwargs = dict(cell=cell, pbc=[True, True, False], half=half, shifts=True, distances=True, vectors=True)
    reference = horizon.search(points, 2.5, backend="serial", **kwargs)
    nl = horizon.search(to_gpu(library, points), 2.5, **kwargs)
    np.testing.assert_array_equal(to_numpy(library, nl.indices), reference.indices)
    np.testing.assert_array_equal(to_numpy(library, nl.shifts), reference.shifts)
    np.testing.assert_array_equal(to_numpy(library, nl.distances), reference.distances)
    np.testing.assert_array_equal(to_numpy(library, nl.vectors), reference.vectors)
    host = nl.to_host()
    np.testing.assert_array_equal(host.vectors, reference.vectors)
    assert horizon.search(to_gpu(library, points), 2.5, cell=cell).shifts is None


@pytest.mark.skipif("torch" not in libraries, reason="needs PyTorch")
def test_a_solver_loop_on_the_gpu():
    points = torch.from_numpy(horizon.random_cloud(100000, seed=3)).cuda()
    for step in range(3):
        points += 0.001 * torch.sin(points + step)
        nl = horizon.search(points, 0.4)
        assert np.array_equal(nl.to_host().indices, horizon.search(points.cpu().numpy(), 0.4).indices)


def test_several_devices_from_python():
    points = horizon.clustered_cloud(200000, clusters=10, sigma=0.7, seed=5)
    nl = horizon.search(points, 0.15, backend="cuda", devices=[0, 0])  # two parts, one GPU is enough
    reference = horizon.search(points, 0.15, backend="serial")
    np.testing.assert_array_equal(nl.offsets, reference.offsets)
    np.testing.assert_array_equal(nl.indices, reference.indices)


@pytest.mark.parametrize("half", [False, True])
def test_parts_kept_on_the_gpus(half):
    points = horizon.clustered_cloud(100000, clusters=8, sigma=0.7, seed=6)
    reference = horizon.search(points, 0.15, half=half, backend="serial")
    parts = horizon.search(points, 0.15, half=half, backend="cuda", devices=[0, 0, 0], keep_on_device=True)
    assert len(parts) == 3 and all(isinstance(p, horizon.DevicePart) for p in parts)
    assert sorted(np.concatenate([p.ids for p in parts]).tolist()) == list(range(len(points)))
    for part in parts:
        rows = part.to_host()
        for r in range(0, len(part), 997):
            np.testing.assert_array_equal(rows.row(r), reference.row(part.ids[r]))
        if libraries:
            np.testing.assert_array_equal(to_numpy(libraries[0], part.device_ids), part.ids)
            np.testing.assert_array_equal(to_numpy(libraries[0], part.indices), rows.indices)
