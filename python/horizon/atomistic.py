"""ASE's neighbour-list functions on horizon's search: the same signatures, quantities and
conventions (ase.neighborlist.neighbor_list and primitive_neighbor_list), without ASE.

    i, j, S, d = horizon.neighbor_list("ijSd", atoms, 5.0)

Entries come ordered by i, then j, then the shift S (ASE orders by i only).
"""
import numpy as np

_SYMBOLS = ("X H He Li Be B C N O F Ne Na Mg Al Si P S Cl Ar K Ca Sc Ti V Cr Mn Fe Co Ni Cu Zn Ga Ge As Se Br Kr "
            "Rb Sr Y Zr Nb Mo Tc Ru Rh Pd Ag Cd In Sn Sb Te I Xe Cs Ba La Ce Pr Nd Pm Sm Eu Gd Tb Dy Ho Er Tm Yb "
            "Lu Hf Ta W Re Os Ir Pt Au Hg Tl Pb Bi Po At Rn Fr Ra Ac Th Pa U Np Pu Am Cm Bk Cf Es Fm Md No Lr Rf "
            "Db Sg Bh Hs Mt Ds Rg Cn Nh Fl Mc Lv Ts Og").split()
_ATOMIC_NUMBERS = {symbol: number for number, symbol in enumerate(_SYMBOLS)}


def _atomic_number(key):
    if isinstance(key, str):
        if key not in _ATOMIC_NUMBERS:
            raise ValueError(f"cutoff: unknown chemical symbol {key!r}")
        return _ATOMIC_NUMBERS[key]
    return int(key)


def primitive_neighbor_list(quantities, pbc, cell, positions, cutoff, numbers=None, self_interaction=False,
                            use_scaled_positions=False, max_nbins=None, *, backend="auto", half=False, threads=0):
    """Every pair of atoms (and periodic images) closer than the cutoff, as ASE's function of the
    same name returns it.

    quantities: letters of "ijdDS", one array each, in that order: i and j (int64 atom indices),
    d (float64 distances), D (float64 (M, 3) vectors x_j + S . cell - x_i), S (int64 (M, 3)
    shifts in cell vectors); pbc: three bools; cell: (3, 3), rows the cell vectors (a vector of
    zeros on an open axis is fine); positions: (N, 3) Cartesian (or fractional, with
    use_scaled_positions); cutoff: a float, one radius per atom (a pair is in when d < r_i +
    r_j), or a dict {(Z1, Z2): cutoff} by atomic number or symbol (pairs not named are out; needs
    numbers); self_interaction: each atom is its own neighbour at S = 0.
    Beyond ASE: backend ("auto", "serial", "openmp", "cuda"), half (each pair once: i < j, or
    i = j with S's first non-zero component positive) and threads. max_nbins is ASE's
    binning limit and has no meaning here.
    """
    from . import search
    del max_nbins  # horizon's grid has no bin limit to set
    positions = np.asarray(positions, dtype=np.float64)
    if positions.ndim != 2 or positions.shape[1] != 3:
        raise ValueError(f"positions must be an (N, 3) array, not shape {positions.shape}")
    cell = np.asarray(cell, dtype=np.float64)
    if use_scaled_positions:
        positions = positions @ cell
    for q in quantities:
        if q not in "ijdDS":
            raise ValueError(f"unsupported quantity {q!r}: each letter must be one of i, j, d, D, S")
    options = dict(backend=backend, half=half, threads=threads, cell=cell, pbc=pbc,
                   self_interaction=self_interaction, shifts="S" in quantities, vectors="D" in quantities,
                   distances="d" in quantities or isinstance(cutoff, dict))
    if isinstance(cutoff, dict):
        if numbers is None:
            raise ValueError("cutoff: a dict of cutoffs per pair of elements needs numbers")
        numbers = np.asarray(numbers)
        table = {}
        for (z1, z2), value in cutoff.items():
            table[_atomic_number(z1), _atomic_number(z2)] = float(value)
            table[_atomic_number(z2), _atomic_number(z1)] = float(value)
        nl = search(positions, max(table.values()), **options)
    elif np.ndim(cutoff) == 0:
        nl = search(positions, float(cutoff), **options)
    else:
        radii = np.asarray(cutoff, dtype=np.float64)
        if radii.shape != (len(positions),):
            raise ValueError(f"cutoff: expected a float, a dict or one radius per atom ({len(positions)}), "
                             f"not shape {radii.shape}")
        nl = search(positions, radii=radii, radius_rule="sum", **options)
    i = np.repeat(np.arange(len(nl), dtype=np.int64), np.diff(nl.offsets))
    j = nl.indices.astype(np.int64)
    keep = None
    if isinstance(cutoff, dict):
        size = 1 + max(int(numbers.max(initial=0)), *(max(pair) for pair in table))
        per_pair = np.zeros((size, size))  # 0 for pairs the dict does not name: never neighbours
        for (z1, z2), value in table.items():
            per_pair[z1, z2] = value
        keep = nl.distances < per_pair[numbers[i], numbers[j]]
    values = {"i": i, "j": j, "d": nl.distances, "D": nl.vectors,
              "S": None if nl.shifts is None else nl.shifts.astype(np.int64)}
    out = tuple(values[q] if keep is None else values[q][keep] for q in quantities)
    return out[0] if len(out) == 1 else out


def neighbor_list(quantities, a, cutoff, self_interaction=False, max_nbins=None, *, backend="auto", half=False,
                  threads=0):
    """ASE's neighbor_list(quantities, atoms, cutoff, self_interaction) for anything with
    get_positions(), cell and pbc (an ase.Atoms, say); get_atomic_numbers() for a dict cutoff.
    See primitive_neighbor_list for the quantities and cutoffs."""
    numbers = a.get_atomic_numbers() if isinstance(cutoff, dict) else None
    return primitive_neighbor_list(quantities, a.pbc, np.asarray(a.cell), a.get_positions(), cutoff,
                                   numbers=numbers, self_interaction=self_interaction, max_nbins=max_nbins,
                                   backend=backend, half=half, threads=threads)
