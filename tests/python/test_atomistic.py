"""horizon.neighbor_list and primitive_neighbor_list against ASE's (Debian's python3-ase) as the
oracle: bulk crystals, skewed and rotated cells, primitive cells with cutoffs of several cells,
slabs, wires and molecules, rattled atoms and atoms outside the cell; float, per-atom and
per-species cutoffs; every backend."""
import numpy as np
import pytest

import horizon

ase = pytest.importorskip("ase")  # the GPU machine's image has no ASE; CI installs it
from ase.build import bulk, fcc111, molecule  # noqa: E402
from ase.neighborlist import natural_cutoffs, neighbor_list as ase_neighbor_list  # noqa: E402

BACKENDS = [b for b in ("serial", "openmp", "cuda") if horizon.backend_available(b)]


def hcp_skewed():
    atoms = bulk("Mg", "hcp", a=3.2, c=5.2)  # a triclinic cell (60 degrees between a and b)
    atoms.rotate(37, (1, 2, 3), rotate_cell=True)  # nothing along the axes
    return atoms


def rattled(atoms, amount=0.08, seed=1):
    atoms = atoms.copy()
    atoms.rattle(amount, seed=seed)
    return atoms


def outside(atoms):
    atoms = atoms.copy()  # every atom moved by whole and half cell vectors: some far outside
    shift = np.random.default_rng(4).integers(-3, 4, size=(len(atoms), 3)) @ atoms.cell
    atoms.positions += shift + 0.5 * atoms.cell[0]
    return atoms


def wire():
    atoms = bulk("Cu", "fcc", a=3.6, cubic=True).repeat((3, 1, 1))
    atoms.pbc = (True, False, False)
    return rattled(atoms)


def systems():
    cu = bulk("Cu", "fcc", a=3.6)
    return {
        "fcc Cu primitive, cutoff 5": (cu, 5.0),
        "fcc Cu primitive, cutoff 5x the cell": (cu, 5 * 2.55),
        "bcc Fe cubic": (bulk("Fe", "bcc", a=2.87, cubic=True), 4.5),
        "diamond Si primitive": (bulk("Si", "diamond", a=5.43), 6.0),
        "diamond Si rattled 2x2x2": (rattled(bulk("Si", "diamond", a=5.43, cubic=True).repeat(2)), 5.0),
        "hcp Mg skewed and rotated": (hcp_skewed(), 7.0),
        "hcp Mg atoms outside the cell": (outside(rattled(hcp_skewed().repeat((2, 2, 1)))), 6.0),
        "Al slab (pbc T T F)": (rattled(fcc111("Al", size=(3, 3, 4), vacuum=6.0)), 5.0),
        "Cu wire (pbc T F F)": (wire(), 4.0),
        "CH4 molecule (no pbc)": (molecule("CH4"), 2.0),
    }


def canonical(i, j, S, *values):
    """The entries sorted by (i, j, S), and the per-entry values in that order."""
    order = np.lexsort((S[:, 2], S[:, 1], S[:, 0], j, i))
    return (np.stack([i, j, *S.T], axis=1)[order],) + tuple(v[order] for v in values)


@pytest.mark.parametrize("name", list(systems()))
@pytest.mark.parametrize("backend", BACKENDS)
def test_float_cutoff_equals_ase(name, backend):
    atoms, cutoff = systems()[name]
    expected = canonical(*ase_neighbor_list("ijSdD", atoms, cutoff))
    got = horizon.neighbor_list("ijSdD", atoms, cutoff, backend=backend)
    assert np.array_equal(canonical(*got)[0], expected[0])
    np.testing.assert_allclose(canonical(*got)[1], expected[1], rtol=1e-12, atol=1e-12 * cutoff)
    np.testing.assert_allclose(canonical(*got)[2], expected[2], rtol=1e-12, atol=1e-12 * cutoff)
    # Ordered by i, then j, then S.
    keys = np.stack([got[0], got[1], *got[2].T], axis=1)
    assert np.array_equal(keys, canonical(*got[:3])[0])


@pytest.mark.parametrize("name", ["fcc Cu primitive, cutoff 5", "diamond Si rattled 2x2x2", "Al slab (pbc T T F)",
                                  "CH4 molecule (no pbc)"])
def test_self_interaction_and_half_lists(name):
    atoms, cutoff = systems()[name]
    i, j, S = horizon.neighbor_list("ijS", atoms, cutoff, self_interaction=True)
    I, J, SS = ase_neighbor_list("ijS", atoms, cutoff, self_interaction=True)
    assert np.array_equal(canonical(i, j, S)[0], canonical(I, J, SS)[0])
    # A half list keeps each pair once: (i, j, S) and (j, i, -S) are one pair.
    hi, hj, hS = horizon.neighbor_list("ijS", atoms, cutoff, half=True)
    fi, fj, fS = horizon.neighbor_list("ijS", atoms, cutoff)
    both = np.concatenate([np.stack([hi, hj, *hS.T], 1), np.stack([hj, hi, *(-hS).T], 1)])
    assert len(hi) * 2 == len(fi)
    assert np.array_equal(np.unique(both, axis=0), canonical(fi, fj, fS)[0])


@pytest.mark.parametrize("name", ["diamond Si rattled 2x2x2", "hcp Mg atoms outside the cell", "Al slab (pbc T T F)"])
def test_per_atom_and_per_species_cutoffs(name):
    atoms, _ = systems()[name]
    radii = np.array(natural_cutoffs(atoms, mult=1.3))
    expected = canonical(*ase_neighbor_list("ijSd", atoms, radii))
    got = canonical(*horizon.neighbor_list("ijSd", atoms, radii))
    assert np.array_equal(got[0], expected[0])
    np.testing.assert_allclose(got[1], expected[1], rtol=1e-12)
    mixed = atoms.copy()
    mixed.numbers[::3] = 8  # a second species
    symbol = mixed.get_chemical_symbols()[1]
    per_pair = {(symbol, symbol): 3.1, (8, symbol): 2.6, ("O", "O"): 4.0}
    expected = canonical(*ase_neighbor_list("ijSd", mixed, per_pair))
    got = canonical(*horizon.neighbor_list("ijSd", mixed, per_pair))
    assert len(got[0]) > 0 and np.array_equal(got[0], expected[0])
    np.testing.assert_allclose(got[1], expected[1], rtol=1e-12)


def test_primitive_neighbor_list_and_scaled_positions():
    from ase.neighborlist import primitive_neighbor_list as ase_primitive
    rng = np.random.default_rng(7)
    cell = np.array([[4.0, 0.0, 0.0], [1.3, 3.5, 0.0], [-0.7, 0.9, 3.8]])
    scaled = rng.random((40, 3))
    pbc = [True, False, True]
    expected = canonical(*ase_primitive("ijSd", pbc, cell, scaled, 4.2, use_scaled_positions=True))
    got = canonical(*horizon.primitive_neighbor_list("ijSd", pbc, cell, scaled, 4.2, use_scaled_positions=True))
    assert np.array_equal(got[0], expected[0])
    np.testing.assert_allclose(got[1], expected[1], rtol=1e-12)
    assert horizon.primitive_neighbor_list("d", pbc, cell, scaled @ cell, 4.2).dtype == np.float64


def test_search_returns_geometry_on_the_list():
    points = horizon.random_cloud(200, seed=2, side=3.0)
    cell = [[3.0, 0, 0], [0.5, 3.0, 0], [0, 0, 3.0]]
    nl = horizon.search(points, 1.7, cell=cell, shifts=True, distances=True, vectors=True)
    assert nl.shifts.shape == (nl.total, 3) and nl.vectors.shape == (nl.total, 3) and nl.distances.shape == (nl.total,)
    i = np.repeat(np.arange(len(nl)), np.diff(nl.offsets))
    D = points[nl.indices] - points[i] + nl.shifts @ np.asarray(cell)
    np.testing.assert_allclose(nl.vectors, D, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(nl.distances, np.linalg.norm(D, axis=1), rtol=1e-12)
    assert (nl.distances < 1.7).all()


@pytest.mark.parametrize("cell, pbc, message", [
    ([[1, 0, 0], [2, 0, 0], [0, 0, 1]], True, "linearly dependent"),
    ([[0, 1, 0], [1, 0, 0], [0, 0, 1]], True, "left-handed"),
    ([[1, 0, 0], [0, 1, 0], [0, 0, 0]], True, "vector c has zero length"),
    ([[1, 0, 0], [0, np.inf, 0], [0, 0, 1]], True, "non-finite"),
    ([[1, 0], [0, 1]], True, r"\(3, 3\) matrix"),
])
def test_bad_cells_are_value_errors(cell, pbc, message):
    with pytest.raises(ValueError, match=message):
        horizon.primitive_neighbor_list("ij", [pbc] * 3, cell, np.zeros((2, 3)), 0.5)
