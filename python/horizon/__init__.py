"""horizon: exact all-pairs fixed-radius neighbour lists (cell lists) for 2-D and 3-D points.

    import horizon
    points = horizon.lattice(100)                 # (10**6, 3) float64
    nl = horizon.search(points, 0.3015)           # every pair closer than the horizon
    nl.offsets, nl.indices                        # CSR: row i is indices[offsets[i]:offsets[i+1]]
    nl.pairs()                                    # (M, 2) int64, i < j, like cKDTree.query_pairs
    nl.to_scipy()                                 # scipy.sparse.csr_matrix of the pattern

The list is exact (the same bits from every backend) and rows are sorted by id unless
sort_rows=False. Errors raise ValueError (bad input) or MemoryError with horizon's message.
"""
import json
import operator
import os

import numpy as np

from . import _horizon

__version__ = _horizon.__version__  # the C++ library's, set by CMake's project(VERSION)

__all__ = ["__version__", "search", "neighbor_list", "primitive_neighbor_list", "warm_up", "NeighborList", "DeviceNeighborList", "DevicePart", "VerletList", "load", "lattice", "random_cloud", "clustered_cloud", "backend_available"]


class NeighborList:
    """A neighbour list in CSR form: row i (the family of point i) is
    indices[offsets[i]:offsets[i + 1]]. offsets is int64 (N + 1), indices int32; when the list
    comes from search() both are read-only views of horizon's buffers (no copy)."""

    shifts = None          #: each entry's periodic shift S, int32 of shape (total, dims), when search(shifts=True)
    distances = None       #: each entry's distance (the norm of D), float64 of shape (total,), when search(distances=True)
    vectors = None         #: each entry's D = x_j + S . cell - x_i, float64 (total, dims), when search(vectors=True)
    backend = None         #: the backend that built the list ("serial", "openmp", "cuda"); None if not searched
    threads = None         #: the threads it used
    backend_choice = None  #: why that backend and thread count (backend="auto" says what it went by)

    def __init__(self, offsets, indices, half=False, references=None):
        self.offsets = offsets
        self.indices = indices
        self.half = bool(half)
        self.references = references  # with a reference set: its size (ids index it), else None

    def __len__(self):
        return len(self.offsets) - 1

    def __repr__(self):
        kind = "half" if self.half else "full"
        return f"<horizon.NeighborList: {len(self)} points, {self.total} entries ({kind})>"

    @property
    def total(self):
        """Number of entries (each pair twice in a full list, once in a half list)."""
        return int(self.offsets[-1])

    def row(self, i):
        """The family of point i (a view)."""
        if not -len(self) <= i < len(self):
            raise IndexError(f"point {i} out of range for {len(self)} points")
        i %= len(self)
        return self.indices[self.offsets[i]:self.offsets[i + 1]]

    def pairs(self):
        """Each pair once, as an (M, 2) int64 array of (i, j) with i < j, sorted."""
        if self.references is not None:
            raise ValueError("pairs() needs one point set; rows of a query list index the references: use to_scipy()")
        rows = np.repeat(np.arange(len(self), dtype=np.int64), np.diff(self.offsets))
        columns = self.indices.astype(np.int64)
        keep = rows < columns
        pairs = np.stack([rows[keep], columns[keep]], axis=1)
        if len(pairs) > 1 and not np.all(np.diff(pairs[:, 0] * len(self) + pairs[:, 1]) > 0):
            pairs = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]  # rows were not sorted
        return pairs

    def to_scipy(self):
        """The pattern as a scipy.sparse.csr_matrix of ones (N x N; queries x references for a
        list against a reference set)."""
        from scipy.sparse import csr_matrix

        n = len(self)
        columns = n if self.references is None else self.references
        return csr_matrix((np.ones(self.total, dtype=np.int8), self.indices, self.offsets), shape=(n, columns))

    def save_vtk(self, path, points, bonds=False, blocks=None):
        """Writes `points` with each family's size (point data "family_size") for ParaView, as
        `horizon search --vtk` does: a VTK XML .vtu file, written to a temporary name and renamed.
        bonds=True adds every pair as a line cell (at most 10**7); blocks (a block id per point)
        adds point data "block"."""
        if bonds and self.references is not None:
            raise ValueError("bonds=True: the rows of a query list index the references; bonds would join unrelated points")
        array = _host_points(points)
        if len(array) != len(self):
            raise ValueError(f"points has {len(array)} rows, the list {len(self)}")
        block_ids = [] if blocks is None else _block_ids(blocks, len(self))
        _horizon.write_vtk(os.fspath(path), array, self.offsets, self.indices, self.half, bool(bonds), block_ids)

    def filter_bonds(self, points, filters, references=None, threads=0):
        """This list without the bonds whose segment x_i -> x_j crosses one of `filters`
        (Peridigm's shapes, pre-notched cracks; `horizon search --bond-filters`), rows in order.
        filters: a list of {"type": "rectangle", "normal": [3], "lower_left_corner": [3],
        "bottom_unit_vector": [3], "bottom_length": b, "side_length": a} and {"type": "disk",
        "center": [3], "normal": [3], "radius": r} (NumPy arrays allowed), or the path of a JSON
        file of them. points: the list's points (2-D points lie in z = 0); references: the
        reference points of a query list."""
        if (references is None) != (self.references is None):
            raise ValueError("references= is needed exactly for a list searched against references")
        array = _host_points(points)
        if len(array) != len(self):
            raise ValueError(f"points has {len(array)} rows, the list {len(self)}")
        reference_array = None if references is None else _host_points(references, "references")
        if isinstance(filters, (str, os.PathLike)):
            source = os.fspath(filters)
            with open(source) as file:
                text = file.read()
        else:
            source = "filters"
            text = json.dumps(list(filters), default=lambda value: np.asarray(value).tolist())
        owned = _horizon.filter_bonds(self.offsets, self.indices, self.half, array, reference_array, text, source,
                                      int(threads))
        return NeighborList(owned.offsets, owned.indices, self.half, self.references)

    def filter_blocks(self, blocks, pairs, reference_blocks=None, threads=0):
        """This list with only the bonds between blocks that are one of `pairs` (Peridigm's block
        rules; `horizon search --block-pairs`), rows in order. blocks: a block id (integer >= 0)
        per point; pairs: "1-1,1-2" or [(1, 1), (1, 2)] (unordered); reference_blocks: the
        blocks of a query list's references."""
        if (reference_blocks is None) != (self.references is None):
            raise ValueError("reference_blocks= is needed exactly for a list searched against references")
        rows = _block_ids(blocks, len(self))
        columns = rows if reference_blocks is None else _block_ids(reference_blocks, self.references, "reference_blocks")
        if not isinstance(pairs, str):
            pairs = ",".join(f"{int(a)}-{int(b)}" for a, b in pairs)
        owned = _horizon.filter_blocks(self.offsets, self.indices, self.half, rows, columns, pairs, int(threads))
        return NeighborList(owned.offsets, owned.indices, self.half, self.references)

    def save(self, prefix):
        """Writes PREFIX.offsets.npy and PREFIX.indices.npy, as the CLI does: each written to a
        temporary name and renamed, the offsets last, so a failure never leaves a list that
        looks complete."""
        for suffix, array in ((".indices.npy", self.indices), (".offsets.npy", self.offsets)):
            target = os.fspath(prefix) + suffix
            temporary = target + ".tmp-" + str(os.getpid())
            try:
                with open(temporary, "wb") as out:
                    np.save(out, np.ascontiguousarray(array))
                os.replace(temporary, target)
            except BaseException:
                if os.path.exists(temporary):
                    os.remove(temporary)
                raise


class VerletList:
    """A Verlet list for moving points (MD, SPH): the pairs within horizon + skin, searched once;
    refresh(points) then gives the exact horizon list of new positions from those candidates,
    equal to search(points, horizon, ...) while needs_rebuild(points) is False, i.e. until some
    point has moved by skin / 2 or more since the build (then build a new VerletList)::

        verlet = horizon.VerletList(x, horizon=0.3, skin=0.03)
        for step in range(steps):
            x = advance(x)
            if verlet.needs_rebuild(x):
                verlet = horizon.VerletList(x, 0.3, 0.03)
            nl = verlet.refresh(x)

    The options are search()'s (host arrays; no periodic box); the list keeps a copy of the
    positions at the build. The number of points and their dimension must stay the same."""

    def __init__(self, points, horizon, skin, *, backend="auto", metric="l2", half=False, sort_rows=True, threads=0,
                 device=0, cells_per_horizon=1):
        if hasattr(points, "__cuda_array_interface__"):
            raise ValueError("VerletList takes host arrays (the GPU Verlet list is not built yet)")
        self.half = bool(half)
        self.threads = int(threads)
        self._owned = _horizon.build_verlet(_host_points(points), float(horizon), float(skin), metric, self.half,
                                            bool(sort_rows), backend, self.threads, int(device),
                                            int(cells_per_horizon))

    def needs_rebuild(self, points):
        """True once a point of `points` has moved by skin / 2 or more since the build."""
        return self._owned.needs_rebuild(_host_points(points), self.threads)

    def refresh(self, points):
        """The exact list of `points` within the horizon, from the stored candidates."""
        owned = self._owned.refresh(_host_points(points), self.threads)
        return NeighborList(owned.offsets, owned.indices, self.half)

    @property
    def candidates(self):
        """The pairs within horizon + skin of the positions at the build (read-only views)."""
        offsets, indices = self._owned.candidate_offsets, self._owned.candidate_indices
        offsets.flags.writeable = False
        indices.flags.writeable = False
        return NeighborList(offsets, indices, self.half)


class _CudaArray:
    """An array in GPU memory (1-D, or rows of `width`), exported through __cuda_array_interface__
    (version 3) so that torch.as_tensor(a, device="cuda") and cupy.asarray(a) take it without a
    copy; it keeps the list that owns the memory alive."""

    def __init__(self, owner, pointer, length, typestr, width=1):
        self._owner = owner
        self.__cuda_array_interface__ = {
            "shape": (length,) if width == 1 else (length, width),
            "typestr": typestr,
            "data": (pointer, False),  # PyTorch refuses read-only arrays; writes change the list
            "strides": None,
            "version": 3,
            "stream": owner.stream or 1,  # the stream it was built on; 1: the legacy default stream
        }

    def __len__(self):
        return self.__cuda_array_interface__["shape"][0]


class DeviceNeighborList:
    """A neighbour list left in GPU memory (search() on a CUDA array): offsets (int64, N + 1) and
    indices (int32) export __cuda_array_interface__, and so do shifts (int32, (total, dims)),
    distances (float64) and vectors (float64, (total, dims)) when asked for (else None);
    to_host() copies it into a NeighborList. The memory goes back to horizon's pool when this
    object and every array taken from it are gone."""

    def __init__(self, owned, half, dims=3):
        self._owned = owned
        self.half = bool(half)
        self.offsets = _CudaArray(owned, owned.offsets_pointer, owned.points + 1, "<i8")
        self.indices = _CudaArray(owned, owned.indices_pointer, owned.total, "<i4")
        self._dims = dims
        for name, typestr, width in (("shifts", "<i4", dims), ("distances", "<f8", 1), ("vectors", "<f8", dims)):
            pointer = getattr(owned, name + "_pointer", 0)
            setattr(self, name, _CudaArray(owned, pointer, owned.total, typestr, width) if pointer else None)

    def __len__(self):
        return self._owned.points

    def __repr__(self):
        kind = "half" if self.half else "full"
        return f"<horizon.DeviceNeighborList: {len(self)} points, {self.total} entries ({kind}), GPU {self.device}>"

    @property
    def total(self):
        return int(self._owned.total)

    @property
    def device(self):
        return self._owned.device

    def to_host(self):
        owned = self._owned.to_host()
        nl = NeighborList(owned.offsets, owned.indices, self.half)
        for name in ("shifts", "distances", "vectors"):
            if getattr(self, name) is not None:
                values = getattr(owned, name)
                setattr(nl, name, values.reshape(-1, self._dims) if name != "distances" else values)
        return nl


class DevicePart(DeviceNeighborList):
    """One GPU's part of search(..., keep_on_device=True): the rows of the points it owns, their
    neighbours as global ids, in its GPU's memory. ids (NumPy, int32) and device_ids (GPU) give
    the global id of each row; halo is the number of points it searched as references only."""

    def __init__(self, owned, half):
        super().__init__(owned, half)
        self.ids = owned.ids
        self.ids.flags.writeable = False
        self.device_ids = _CudaArray(owned, owned.ids_pointer, owned.points, "<i4")
        self.halo = int(owned.halo)

    def __repr__(self):
        kind = "half" if self.half else "full"
        return (f"<horizon.DevicePart: {len(self)} points + {self.halo} halo, {self.total} entries ({kind}), "
                f"GPU {self.device}>")


def _search_on_gpu(points, horizon, metric, half, sort_rows, cells_per_horizon, box, cell, pbc, self_interaction,
                   outputs):
    interface = points.__cuda_array_interface__
    shape, typestr = tuple(interface["shape"]), interface["typestr"]
    if len(shape) != 2 or shape[1] not in (2, 3):
        raise ValueError(f"points must be an (N, 2) or (N, 3) array, not shape {shape}")
    if typestr != "<f8":
        raise ValueError(f"GPU points must be float64 ('<f8'), not '{typestr}' (convert them on the GPU first, "
                         "e.g. x.double() or x.astype(cupy.float64))")
    strides = interface.get("strides")
    if strides is not None and tuple(strides) != (8 * shape[1], 8):
        raise ValueError(f"GPU points must be C-contiguous (strides {(8 * shape[1], 8)}, not {tuple(strides)}); "
                         "e.g. x.contiguous() or cupy.ascontiguousarray(x)")
    stream = interface.get("stream") or 0
    owned = _horizon.search_device(interface["data"][0], shape[0], shape[1], stream, float(horizon), metric,
                                   bool(half), bool(sort_rows), int(cells_per_horizon), _periods(box, shape[1]),
                                   *_cell_and_pbc(cell, pbc, shape[1]), bool(self_interaction), outputs)
    return DeviceNeighborList(owned, half, shape[1])


def _host_points(points, name="points"):
    """`points` as the C-contiguous (N, 2|3) float64/float32 array horizon reads (no copy when it is one)."""
    array = np.asarray(points)
    if array.ndim != 2 or array.shape[1] not in (2, 3):
        raise ValueError(f"{name} must be an (N, 2) or (N, 3) array, not shape {array.shape}")
    if array.dtype not in (np.float64, np.float32):
        if not (np.issubdtype(array.dtype, np.floating) or np.issubdtype(array.dtype, np.integer)):
            raise ValueError(f"{name} must be numbers, not {array.dtype}")
        array = array.astype(np.float64)
    return np.ascontiguousarray(array)  # AoS is what horizon reads


def _block_ids(blocks, count, name="blocks"):
    """blocks as the list of int32 block ids horizon takes, checked."""
    array = np.asarray(blocks)
    if array.shape != (count,) or not np.issubdtype(array.dtype, np.integer):
        raise ValueError(f"{name} must be {count} integer block ids, not an array of shape {array.shape} and dtype {array.dtype}")
    if count and (array.min() < 0 or array.max() > 2**31 - 1):
        raise ValueError(f"{name}: block ids must lie in 0 .. 2**31 - 1")
    return array.astype(np.int32).tolist()


def _periods(box, dims):
    """box as the three periods horizon takes (0: open axis)."""
    if box is None:
        return [0.0, 0.0, 0.0]
    periods = [float(p) for p in np.atleast_1d(np.asarray(box, dtype=np.float64))]
    if len(periods) not in (2, 3) or len(periods) < dims:
        raise ValueError(f"box must give a period for each of the {dims} axes (0 for an open one), not {box!r}")
    return periods + [0.0] * (3 - len(periods))


def _cell_and_pbc(cell, pbc, dims):
    """cell ((dims, dims) or (3, 3) array-like, or None) and pbc as the 3 x 3 rows and 3 flags
    horizon takes."""
    if cell is None:
        if pbc is not None:
            raise ValueError("pbc= needs cell=")
        return None, [False, False, False]
    matrix = np.asarray(cell, dtype=np.float64)
    if matrix.shape not in ((dims, dims), (3, 3)):
        raise ValueError(f"cell must be a ({dims}, {dims}) or (3, 3) matrix (rows: the cell vectors), not shape {matrix.shape}")
    rows = np.zeros((3, 3))
    rows[:matrix.shape[0], :matrix.shape[1]] = matrix
    flags = [True] * dims if pbc is None else [bool(f) for f in np.atleast_1d(pbc)]
    if len(flags) == 1:
        flags *= dims
    if len(flags) not in (dims, 3) or any(flags[dims:]):
        raise ValueError(f"pbc must give a flag for each of the {dims} cell vectors, not {pbc!r}")
    return rows.tolist(), flags + [False] * (3 - len(flags))


def search(points, horizon=None, *, backend="auto", metric="l2", half=False, sort_rows=True, threads=0, device=0,
           devices=None, cells_per_horizon=1, box=None, references=None, radii=None, radius_rule="gather",
           gpu_max_memory=0, cell=None, pbc=None, self_interaction=False, shifts=False, distances=False,
           vectors=False, keep_on_device=False):
    """The neighbour list of `points` ((N, 2) or (N, 3) array-like, float64 or float32, any
    order): row i holds every j != i with distance(i, j) < horizon.

    backend: "auto" (by the problem and the machine: one core, the free cores or the GPU), "serial",
    "openmp" or "cuda";
    metric: "l2", "l1" or "linf"; half: keep each pair once, in the row of the smaller id;
    sort_rows: rows ascending by id (False is faster); threads: openmp threads (0: all);
    device: CUDA device; devices: several CUDA devices, one part of the points each;
    cells_per_horizon: cell side horizon / k (1-3);
    box: periods (Lx, Ly[, Lz]) of a periodic box, 0 for an open axis (scipy's boxsize): points in
    [0, L), nearest-image distances, horizon < L/2;
    references: a second point set: row i then holds every reference j with distance < horizon
    (scipy's query_ball_point; nothing is excluded as self) and the list's references is its size;
    radii: instead of horizon, one radius per point (N floats, finite and > 0) and radius_rule says
    which a pair is tested with: "gather" (d < r_i, scipy's query_ball_point with an array of r),
    "scatter" (d < r_j), "max" or "min" (d < max/min(r_i, r_j); the only rules with half=True);
    with references, one radius per query and the gather rule only;
    gpu_max_memory: most bytes of GPU memory the search may take (0: what is free), for a solver
    that keeps its own arrays on the same GPU;
    cell: a periodic cell of any shape instead of box, its rows the cell vectors ((3, 3), or (2, 2)
    for 2-D points), with pbc (a bool per cell vector; default all True): points anywhere, any
    horizon however small the cell; row i lists every image of every j within the horizon, each
    an entry of its own, ordered by j, then by shift (radius_rule="sum" is ASE's r_i + r_j);
    self_interaction: i is its own neighbour at shift 0;
    shifts, distances, vectors: per-entry arrays on the list (nl.shifts, nl.distances,
    nl.vectors: S, the distance and D = x_j + S . cell - x_i), computed as each pair is found.

    A CUDA array (__cuda_array_interface__: CuPy, PyTorch; float64, C-contiguous) is searched
    where it lies, on its GPU and stream, and gives a DeviceNeighborList, its outputs on the GPU
    too (backend, threads and device do not apply; radii and references need host arrays).

    keep_on_device (backend="cuda"): the points cut into one part per entry of devices (or device
    alone), each part's rows left on its GPU: a list of DevicePart, one per GPU, whose rows
    together are the list.
    """
    if (horizon is None) == (radii is None):
        raise ValueError("give either horizon or radii (one radius per point)")
    if hasattr(points, "__cuda_array_interface__"):
        if radii is not None:
            raise ValueError("radii= is not supported for GPU arrays yet: pass host arrays (backend='cuda' still runs on the GPU)")
        if references is not None:
            raise ValueError("references= is not supported for GPU arrays yet: pass host arrays (backend='cuda' "
                             "still runs on the GPU)")
        return _search_on_gpu(points, horizon, metric, half, sort_rows, cells_per_horizon, box, cell, pbc,
                              self_interaction, [bool(shifts), bool(distances), bool(vectors)])
    array = _host_points(points)
    if keep_on_device:
        if backend != "cuda":
            raise ValueError(f"keep_on_device=True needs backend='cuda', not {backend!r}")
        if radii is not None or box is not None or references is not None or cell is not None or shifts or \
                distances or vectors:
            raise ValueError("keep_on_device=True: radii=, box=, references=, cell= and the per-entry outputs "
                             "are not supported")
        parts = _horizon.search_device_parts(array, float(horizon), metric, bool(half), bool(sort_rows), int(device),
                                             [int(d) for d in (devices or [])], int(cells_per_horizon),
                                             _byte_count(gpu_max_memory, "gpu_max_memory"))
        return [DevicePart(part, half) for part in parts]
    reference_array = None if references is None else _host_points(references, "references")
    if reference_array is not None and reference_array.shape[1] != array.shape[1]:
        raise ValueError(f"references have {reference_array.shape[1]} coordinates, points {array.shape[1]}")
    radius_array = None
    if radii is not None:
        radius_array = np.ascontiguousarray(radii, dtype=np.float64)
        if radius_array.shape != (len(array),):
            raise ValueError(f"radii: expected shape ({len(array)},), one radius per point; got {radius_array.shape}")
    owned = _horizon.search(array, 0.0 if horizon is None else float(horizon), metric, bool(half), bool(sort_rows),
                            backend, int(threads), int(device), [int(d) for d in (devices or [])],
                            int(cells_per_horizon), _periods(box, array.shape[1]), reference_array, radius_array,
                            str(radius_rule), _byte_count(gpu_max_memory, "gpu_max_memory"),
                            *_cell_and_pbc(cell, pbc, array.shape[1]), bool(self_interaction),
                            [bool(shifts), bool(distances), bool(vectors)])
    offsets, indices = owned.offsets, owned.indices
    offsets.flags.writeable = False
    indices.flags.writeable = False
    nl = NeighborList(offsets, indices, half, None if reference_array is None else len(reference_array))
    dims = array.shape[1]
    for name, wanted, width in (("shifts", shifts, dims), ("distances", distances, 1), ("vectors", vectors, dims)):
        if wanted:
            values = getattr(owned, name)
            values.flags.writeable = False
            setattr(nl, name, values.reshape(-1, width) if width > 1 else values)
    nl.backend, nl.threads, nl.backend_choice = owned.backend, owned.threads, owned.choice
    return nl


def warm_up(backend="auto"):
    """Pays now what a first search on `backend` would pay (the thread pool, the SIMD dispatch, a
    GPU's context and memory pool), so that a solver's first step costs what the others do."""
    _horizon.warm_up(str(backend))


def _byte_count(value, name):
    count = operator.index(value)
    if count < 0:
        raise ValueError(f"{name}: expected a number of bytes >= 0, not {count}")
    return count


def load(prefix, half=False):
    """The list a search saved (NeighborList.save or `horizon search --out PREFIX`)."""
    prefix = os.fspath(prefix)
    offsets_path, indices_path = prefix + ".offsets.npy", prefix + ".indices.npy"
    offsets = np.load(offsets_path, allow_pickle=False)
    indices = np.load(indices_path, allow_pickle=False)
    if offsets.ndim != 1 or offsets.dtype != np.int64 or len(offsets) == 0:
        raise ValueError(f"{offsets_path}: expected a 1-D int64 array of N + 1 offsets")
    if indices.ndim != 1 or indices.dtype not in (np.int32, np.int64):
        raise ValueError(f"{indices_path}: expected a 1-D int32 or int64 array")
    if offsets[0] != 0 or offsets[-1] != len(indices) or np.any(np.diff(offsets) < 0):
        raise ValueError(f"{offsets_path}: offsets must rise from 0 to {len(indices)}, the entries of {indices_path}")
    if len(indices) and (indices.min() < 0 or indices.max() >= len(offsets) - 1):
        raise ValueError(f"{indices_path}: an id lies outside 0 .. {len(offsets) - 2}")
    return NeighborList(offsets, indices.astype(np.int32, copy=False), half)


def lattice(n, dims=3, side=10.0):
    """n^dims points on a regular lattice of spacing side / n (the benchmark problems)."""
    return _horizon.lattice(int(n), int(dims), float(side))


def random_cloud(count, dims=3, seed=1, side=10.0):
    """count points uniform in [0, side)^dims."""
    return _horizon.random_cloud(int(count), int(dims), int(seed), float(side))


def clustered_cloud(count, clusters=64, sigma=1.0, dims=3, seed=1, side=10.0):
    """count points in `clusters` Gaussian blobs of standard deviation sigma."""
    return _horizon.clustered_cloud(int(count), int(clusters), float(sigma), int(dims), int(seed), float(side))


def backend_available(name):
    """Whether a backend ("serial", "openmp", "cuda") is built and has hardware here."""
    return _horizon.backend_available(name)


from .atomistic import neighbor_list, primitive_neighbor_list  # noqa: E402 (they call search())
