"""The Python package against a NumPy brute force, scipy, and the CLI's files."""
import os
import subprocess
import threading

import numpy as np
import pytest

import horizon


def brute_force(points, h, metric="l2", half=False):
    """Rows of the list by the definition, with horizon's arithmetic ((dx*dx + dy*dy) + dz*dz < h*h)."""
    p = np.asarray(points, dtype=np.float64)
    d = p[:, None, :] - p[None, :, :]
    if metric == "l2":
        acc = d[..., 0] * d[..., 0] + d[..., 1] * d[..., 1]
        if p.shape[1] == 3:
            acc = acc + d[..., 2] * d[..., 2]
        near = acc < h * h
    elif metric == "l1":
        near = np.abs(d).sum(axis=2) < h
    else:
        near = np.abs(d).max(axis=2) < h
    np.fill_diagonal(near, False)
    if half:
        near = np.triu(near)
    return [np.flatnonzero(row) for row in near]


def rows_of(nl):
    return [nl.row(i) for i in range(len(nl))]


@pytest.mark.parametrize("dims", [2, 3])
@pytest.mark.parametrize("metric", ["l2", "l1", "linf"])
@pytest.mark.parametrize("half", [False, True])
def test_matches_brute_force(dims, metric, half):
    points = horizon.random_cloud(1500, dims=dims, seed=3)
    h = 0.9 if dims == 3 else 0.4
    nl = horizon.search(points, h, metric=metric, half=half)
    expected = brute_force(points, h, metric, half)
    assert len(nl) == len(points)
    assert nl.total == sum(len(r) for r in expected)
    for got, want in zip(rows_of(nl), expected):
        np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("backend", ["serial", "openmp", "cuda"])
def test_every_backend_gives_the_same_list(backend):
    if not horizon.backend_available(backend):
        pytest.skip(f"{backend} is not available here")
    points = horizon.clustered_cloud(20000, clusters=8, sigma=0.5, seed=2)
    reference = horizon.search(points, 0.2, backend="serial")
    nl = horizon.search(points, 0.2, backend=backend)
    np.testing.assert_array_equal(nl.offsets, reference.offsets)
    np.testing.assert_array_equal(nl.indices, reference.indices)


def test_pairs_and_scipy_agree_with_ckdtree():
    from scipy.spatial import cKDTree

    points = horizon.random_cloud(5000, seed=5)
    nl = horizon.search(points, 0.5)
    expected = cKDTree(points).query_pairs(0.5, output_type="ndarray")  # no pair lies at exactly 0.5
    expected = expected[np.lexsort((expected[:, 1], expected[:, 0]))]
    np.testing.assert_array_equal(nl.pairs(), expected)
    matrix = nl.to_scipy()
    assert matrix.shape == (5000, 5000) and matrix.nnz == nl.total
    assert (matrix != matrix.T).nnz == 0


def test_unsorted_rows_give_the_same_pairs():
    points = horizon.random_cloud(4000, seed=6)
    np.testing.assert_array_equal(horizon.search(points, 0.6, sort_rows=False).pairs(), horizon.search(points, 0.6).pairs())


def test_input_layouts_and_types():
    points = horizon.random_cloud(2000, seed=7)
    reference = horizon.search(points, 0.8)
    single = points.astype(np.float32)
    promoted = horizon.search(single.astype(np.float64), 0.8)
    np.testing.assert_array_equal(horizon.search(single, 0.8).indices, promoted.indices)
    np.testing.assert_array_equal(horizon.search(np.asfortranarray(points), 0.8).indices, reference.indices)
    np.testing.assert_array_equal(horizon.search(points.tolist(), 0.8).indices, reference.indices)
    lattice = horizon.lattice(6)
    np.testing.assert_array_equal(horizon.search((lattice * 2).astype(np.int64), 2.5).indices,
                                  horizon.search(lattice * 2, 2.5).indices)


def test_arrays_view_the_list_without_a_copy_and_keep_it_alive():
    nl = horizon.search(horizon.lattice(10), 1.5)
    offsets, indices = nl.offsets, nl.indices
    assert offsets.dtype == np.int64 and indices.dtype == np.int32
    assert offsets.base is not None and indices.base is not None
    assert not offsets.flags.writeable and not indices.flags.writeable
    del nl
    assert offsets[-1] == len(indices) and indices.max() < 1000


def test_clear_errors():
    points = horizon.random_cloud(100, seed=1)
    points[42, 1] = np.nan
    with pytest.raises(ValueError, match="42"):
        horizon.search(points, 0.5)
    with pytest.raises(ValueError, match="shape"):
        horizon.search(np.zeros((10, 4)), 0.5)
    with pytest.raises(ValueError, match="horizon"):
        horizon.search(horizon.random_cloud(10), -1.0)
    with pytest.raises(ValueError, match="backend"):
        horizon.search(horizon.random_cloud(10), 0.5, backend="quantum")
    with pytest.raises(ValueError, match="metric"):
        horizon.search(horizon.random_cloud(10), 0.5, metric="cosine")
    with pytest.raises(ValueError, match="cuda backend"):
        horizon.search(horizon.random_cloud(10), 0.5, backend="serial", devices=[0, 1])
    with pytest.raises(ValueError, match="backend='cuda'"):
        horizon.search(horizon.random_cloud(10), 0.5, keep_on_device=True)
    with pytest.raises(ValueError, match="not supported"):
        horizon.search(horizon.random_cloud(10), 0.5, backend="cuda", keep_on_device=True, box=[1, 1, 1])
    if not horizon.backend_available("cuda"):
        with pytest.raises(ValueError, match="CUDA"):
            horizon.search(horizon.random_cloud(10), 0.5, backend="cuda", keep_on_device=True)


def test_gpu_max_memory_gives_the_same_list():
    # 216,000 points, a 105 MB list: on a GPU, a 60 MB limit makes the search fill it in batches.
    points = horizon.lattice(60)
    expected = horizon.search(points, 0.5025, backend="serial")
    backend = "cuda" if horizon.backend_available("cuda") else "serial"
    limited = horizon.search(points, 0.5025, backend=backend, gpu_max_memory=60 << 20)
    assert np.array_equal(limited.offsets, expected.offsets) and np.array_equal(limited.indices, expected.indices)
    with pytest.raises(ValueError, match="gpu_max_memory"):
        horizon.search(points, 0.5025, gpu_max_memory=-1)


def test_the_gil_is_released_during_a_search():
    points = horizon.random_cloud(300000, seed=8)
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)

    counter = threading.Thread(target=count)
    counter.start()
    horizon.search(points, 0.3, backend="serial")
    done.set()
    counter.join()
    assert len(ticks) > 100  # the other thread ran while the search did


def test_save_and_load(tmp_path):
    nl = horizon.search(horizon.random_cloud(3000, seed=9), 0.7, half=True)
    nl.save(tmp_path / "list")
    back = horizon.load(tmp_path / "list", half=True)
    np.testing.assert_array_equal(back.offsets, nl.offsets)
    np.testing.assert_array_equal(back.indices, nl.indices)
    assert sorted(os.listdir(tmp_path)) == ["list.indices.npy", "list.offsets.npy"]
    np.save(tmp_path / "list.offsets.npy", nl.offsets * 2)  # offsets that do not match the indices
    with pytest.raises(ValueError, match="offsets.npy"):
        horizon.load(tmp_path / "list")


def test_loads_what_the_cli_wrote(tmp_path):
    cli = os.environ.get("HORIZON_CLI")
    if not cli:
        pytest.skip("HORIZON_CLI not set")
    subprocess.run([cli, "search", "lattice:12", "--horizon", "2.0", "--out", str(tmp_path / "cli"), "--quiet"],
                   check=True)
    nl = horizon.load(tmp_path / "cli")
    reference = horizon.search(horizon.lattice(12), 2.0)
    np.testing.assert_array_equal(nl.offsets, reference.offsets)
    np.testing.assert_array_equal(nl.indices, reference.indices)


@pytest.mark.parametrize("dims", [2, 3])
def test_periodic_box_matches_ckdtree_boxsize(dims):
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(11)
    box = [4.0, 5.0, 6.0][:dims]
    points = rng.random((3000, dims)) * box
    nl = horizon.search(points, 0.7, box=box)
    expected = cKDTree(points, boxsize=box).query_pairs(0.7, output_type="ndarray")  # <= r: no ties here
    expected = expected[np.lexsort((expected[:, 1], expected[:, 0]))]
    assert np.array_equal(nl.pairs(), expected)


def test_periodic_box_with_an_open_axis():
    rng = np.random.default_rng(12)
    points = rng.random((1000, 3)) * [3.0, 3.0, 9.0]
    nl = horizon.search(points, 0.5, box=[3.0, 3.0, 0])  # z open
    shifted = points.copy()
    shifted[:, 2] += 100.0  # an open axis is not wrapped: moving along it changes nothing
    assert np.array_equal(nl.indices, horizon.search(shifted, 0.5, box=[3.0, 3.0, 0]).indices)
    with pytest.raises(ValueError, match="box"):
        horizon.search(points, 0.5, box=[3.0])
    with pytest.raises(ValueError):
        horizon.search(points * 2, 0.5, box=[3.0, 3.0, 0])  # points outside [0, L)


def test_references_match_query_ball_point():
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(13)
    references = rng.random((4000, 3)) * 10
    queries = rng.random((700, 3)) * 10
    nl = horizon.search(queries, 0.8, references=references)
    assert len(nl) == len(queries) and nl.references == len(references)
    expected = cKDTree(references).query_ball_point(queries, 0.8)
    for i, row in enumerate(expected):
        assert np.array_equal(nl.row(i), np.sort(row))
    assert nl.to_scipy().shape == (len(queries), len(references))
    with pytest.raises(ValueError, match="pairs"):
        nl.pairs()


@pytest.mark.parametrize("rule", ["gather", "scatter", "max", "min"])
@pytest.mark.parametrize("backend", ["serial", "openmp"])
def test_radii_match_brute_force_and_query_ball_point(rule, backend):
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(21)
    points = rng.random((1500, 3)) * 10
    radii = 0.4 * np.exp(rng.uniform(0, np.log(10), len(points)))  # spanning 10x
    nl = horizon.search(points, radii=radii, radius_rule=rule, backend=backend)
    d = points[:, None, :] - points[None, :, :]
    acc = (d[..., 0] * d[..., 0] + d[..., 1] * d[..., 1]) + d[..., 2] * d[..., 2]
    r = {"gather": radii[:, None], "scatter": radii[None, :], "max": np.maximum.outer(radii, radii),
         "min": np.minimum.outer(radii, radii)}[rule]
    near = acc < r * r
    np.fill_diagonal(near, False)
    assert all(np.array_equal(nl.row(i), np.flatnonzero(near[i])) for i in range(len(points)))
    if rule == "gather":  # scipy's query_ball_point with an array of radii (ties have probability 0 here)
        expected = cKDTree(points).query_ball_point(points, radii)
        assert all(np.array_equal(nl.row(i), np.setdiff1d(row, [i])) for i, row in enumerate(expected))
    if rule in ("max", "min"):
        half = horizon.search(points, radii=radii, radius_rule=rule, half=True)
        assert all(np.array_equal(half.row(i), np.flatnonzero(np.triu(near)[i])) for i in range(len(points)))


@pytest.mark.parametrize("backend", ["serial", "openmp"])
def test_radii_of_queries_match_query_ball_point(backend):
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(22)
    references = rng.random((2000, 3)) * 10
    queries = np.vstack([rng.random((500, 3)) * 10, references[:100]])  # some queries on references
    radii = 0.3 * np.exp(rng.uniform(0, np.log(10), len(queries)))
    nl = horizon.search(queries, radii=radii, references=references, backend=backend)
    assert nl.references == len(references)
    expected = cKDTree(references).query_ball_point(queries, radii)
    assert all(np.array_equal(nl.row(i), np.sort(row)) for i, row in enumerate(expected))
    with pytest.raises(ValueError, match="only radius_rule='gather'"):
        horizon.search(queries, radii=radii, references=references, radius_rule="max")


def test_radii_errors():
    points = np.zeros((5, 3))
    with pytest.raises(ValueError, match="point 2 has radius -1"):
        horizon.search(points, radii=[1, 1, -1, 1, 1])
    with pytest.raises(ValueError, match="one radius per point"):
        horizon.search(points, radii=[1, 1])
    with pytest.raises(ValueError, match="either horizon or radii"):
        horizon.search(points, 1.0, radii=[1] * 5)
    with pytest.raises(ValueError, match="either horizon or radii"):
        horizon.search(points)
    with pytest.raises(ValueError, match="symmetric rule"):
        horizon.search(points, radii=[1] * 5, half=True)
    with pytest.raises(ValueError, match="unknown radius rule"):
        horizon.search(points, radii=[1] * 5, radius_rule="mean")


@pytest.mark.parametrize("bonds", [False, True])
@pytest.mark.parametrize("dims", [2, 3])
def test_save_vtk_reads_back_with_meshio(tmp_path, bonds, dims):
    meshio = pytest.importorskip("meshio")
    points = horizon.random_cloud(800, dims=dims, seed=5)
    nl = horizon.search(points, 1.2 if dims == 3 else 0.5)
    path = tmp_path / "cloud.vtu"
    nl.save_vtk(path, points, bonds=bonds)
    mesh = meshio.read(path)
    expected_xyz = np.zeros((len(points), 3))
    expected_xyz[:, :dims] = points
    assert np.array_equal(mesh.points, expected_xyz)
    assert np.array_equal(mesh.point_data["family_size"], np.diff(nl.offsets))
    cells = {block.type: block.data for block in mesh.cells}
    assert np.array_equal(cells["vertex"].ravel(), np.arange(len(points)))
    if bonds:
        assert np.array_equal(cells["line"], nl.pairs())
    else:
        assert "line" not in cells
    assert not [f for f in os.listdir(tmp_path) if ".tmp." in f]


def test_save_vtk_of_a_half_list_draws_each_pair_once(tmp_path):
    meshio = pytest.importorskip("meshio")
    points = horizon.random_cloud(500, seed=6)
    half = horizon.search(points, 1.3, half=True)
    half.save_vtk(tmp_path / "half.vtu", points, bonds=True)
    lines = {block.type: block.data for block in meshio.read(tmp_path / "half.vtu").cells}["line"]
    assert np.array_equal(lines, horizon.search(points, 1.3).pairs())


def _segment_crosses_plane_x(points, pairs, x0):
    """Brute force for a disk in the plane x = x0 wider than the cloud: ends on opposite sides, or one on it."""
    a, b = points[pairs[:, 0], 0] - x0, points[pairs[:, 1], 0] - x0
    return ((a < 0) & (b > 0)) | ((a > 0) & (b < 0)) | ((a == 0) != (b == 0))


@pytest.mark.parametrize("half", [False, True])
def test_filter_bonds_drops_the_bonds_a_crack_crosses(tmp_path, half):
    points = horizon.random_cloud(2000, seed=9)
    nl = horizon.search(points, 1.0, half=half)
    crack = [{"type": "disk", "center": np.array([5.0, 5.0, 5.0]), "normal": [1, 0, 0], "radius": 100.0}]
    kept = nl.filter_bonds(points, crack)
    pairs = nl.pairs()
    expected = pairs[~_segment_crosses_plane_x(points, pairs, 5.0)]
    assert np.array_equal(kept.pairs(), expected)
    assert kept.half == half and 0 < kept.total < nl.total
    (tmp_path / "crack.json").write_text('[{"type": "disk", "center": [5, 5, 5], "normal": [1, 0, 0], "radius": 100}]')
    assert np.array_equal(nl.filter_bonds(points, tmp_path / "crack.json").indices, kept.indices)
    with pytest.raises(ValueError, match="filters: filter 0: missing key 'radius'"):
        nl.filter_bonds(points, [{"type": "disk", "center": [0, 0, 0], "normal": [0, 0, 1]}])
    with pytest.raises(ValueError, match="rows"):
        nl.filter_bonds(points[:10], crack)


def test_filter_blocks_keeps_the_pairs_and_writes_blocks_to_vtk(tmp_path):
    points = horizon.random_cloud(1500, seed=10)
    blocks = (points[:, 0] > 5).astype(np.int64) + 1  # block 1 left of x = 5, block 2 right
    nl = horizon.search(points, 1.0)
    kept = nl.filter_blocks(blocks, "1-1,2-2")
    pairs = nl.pairs()
    assert np.array_equal(kept.pairs(), pairs[blocks[pairs[:, 0]] == blocks[pairs[:, 1]]])
    assert np.array_equal(nl.filter_blocks(blocks, [(1, 1), (2, 2)]).indices, kept.indices)
    assert nl.filter_blocks(blocks, "1-2,1-1,2-2").total == nl.total
    with pytest.raises(ValueError, match="no point is in block 3"):
        nl.filter_blocks(blocks, "1-3")
    with pytest.raises(ValueError, match="integer block ids"):
        nl.filter_blocks(blocks[:5], "1-1")
    meshio = pytest.importorskip("meshio")
    kept.save_vtk(tmp_path / "blocks.vtu", points, blocks=blocks)
    assert np.array_equal(meshio.read(tmp_path / "blocks.vtu").point_data["block"], blocks)


def test_filters_of_a_query_list_use_the_references():
    queries, references = horizon.random_cloud(300, seed=11), horizon.random_cloud(1000, seed=12)
    nl = horizon.search(queries, 1.2, references=references)
    query_blocks, reference_blocks = np.arange(300) % 2, np.arange(1000) % 3
    kept = nl.filter_blocks(query_blocks, "0-0,1-2", reference_blocks=reference_blocks)
    for i in range(0, 300, 37):
        row = nl.row(i)
        allowed = {0: {0}, 1: {2}}[query_blocks[i]]
        assert np.array_equal(kept.row(i), row[np.isin(reference_blocks[row], list(allowed))])
    crack = [{"type": "disk", "center": [5, 5, 5], "normal": [1, 0, 0], "radius": 100}]
    cut = nl.filter_bonds(queries, crack, references=references)
    for i in range(0, 300, 37):
        row = nl.row(i)
        a, b = queries[i, 0] - 5, references[row, 0] - 5
        crosses = ((a < 0) & (b > 0)) | ((a > 0) & (b < 0)) | ((a == 0) != (b == 0))
        assert np.array_equal(cut.row(i), row[~crosses])
    with pytest.raises(ValueError, match="references="):
        nl.filter_bonds(queries, crack)


@pytest.mark.parametrize("half", [False, True])
def test_verlet_list_refreshes_moved_points_exactly_until_a_rebuild_is_due(half):
    rng = np.random.default_rng(3)
    points = horizon.random_cloud(3000, 3, 5, 4.0)
    h, skin = 0.4, 0.1
    verlet = horizon.VerletList(points, h, skin, half=half, backend="openmp")
    wider = horizon.search(points, h + skin, half=half)
    assert np.array_equal(verlet.candidates.offsets, wider.offsets)
    assert np.array_equal(verlet.candidates.indices, wider.indices)
    for _ in range(3):  # moves of up to skin / 5 per axis: at most 0.35 skin in all
        moved = points + rng.uniform(-skin / 5, skin / 5, points.shape)
        assert not verlet.needs_rebuild(moved)
        refreshed = verlet.refresh(moved)
        assert [list(r) for r in rows_of(refreshed)] == [list(r) for r in brute_force(moved, h, half=half)]
    far = points.copy()
    far[1234] += [0.0, skin / 2, 0.0]
    assert verlet.needs_rebuild(far)


def test_verlet_list_errors():
    points = horizon.random_cloud(100, 3, 1)
    with pytest.raises(ValueError, match="skin must be finite and > 0"):
        horizon.VerletList(points, 0.5, 0.0)
    verlet = horizon.VerletList(points, 0.5, 0.1)
    with pytest.raises(ValueError, match="built for 100 points"):
        verlet.refresh(points[:99])
    with pytest.raises(ValueError, match="built for 100 points"):
        verlet.needs_rebuild(points[:, :2])
