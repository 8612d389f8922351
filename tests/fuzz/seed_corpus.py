"""Writes the fuzz targets' first inputs (valid files of every accepted form) into corpus/.
The fuzzer's own finds are merged in by `make fuzz`. Run from anywhere: /usr/bin/python3 seed_corpus.py"""
import io
import json
import pathlib
import struct

import numpy as np

corpus = pathlib.Path(__file__).resolve().parent / "corpus"


def npy(array, version=None, fortran=False):
    buffer = io.BytesIO()
    array = np.asfortranarray(array) if fortran else array
    if version is None:
        np.save(buffer, array)
    else:
        np.lib.format.write_array(buffer, array, version=version)
    return buffer.getvalue()


def seed(target, name, data):
    (corpus / target).mkdir(parents=True, exist_ok=True)
    (corpus / target / name).write_bytes(data.encode() if isinstance(data, str) else data)


rng = np.random.default_rng(1)
points = rng.random((5, 3))
seed("npy_points", "f8_3d", npy(points))
seed("npy_points", "f4_2d", npy(points[:, :2].astype(np.float32)))
seed("npy_points", "fortran", npy(points, fortran=True))
seed("npy_points", "version2", npy(points, version=(2, 0)))
seed("npy_points", "empty", npy(np.zeros((0, 3))))
seed("npy_points", "nan", npy(np.array([[0.0, np.nan, 1.0]])))

seed("text_points", "xyz", "0 0 0\n1 2 3\n-1.5e-3 4 5\n")
seed("text_points", "csv_header", "x,y,z\n0,0,0\n1,2,3\n")
seed("text_points", "plane", "# 2-D\n0.5 0.25\n1 1 # comment\n\n2 2\n")
seed("text_points", "peridigm", "# x y z block volume\n0 0 0 1 0.001\n1 0 0 2 0.001\n")
seed("text_points", "infinite", "0 0 inf\n")

seed("extxyz", "silicon", '2\nLattice="0 2.715 2.715 2.715 0 2.715 2.715 2.715 0" Properties=species:S:1:pos:R:3 '
     'pbc="T T T"\nSi 0 0 0\nSi 1.3575 1.3575 1.3575\n')
seed("extxyz", "slab_columns", '2\nLattice="3 0 0 0 3 0 0 0 0" pbc="T T F" Properties=species:S:1:pos:R:3:forces:R:3 '
     'energy=-1.5\nAl 0 0 0 0.1 0.2 0.3\nAl 1.5 1.5 1 0 0 0\n')
seed("extxyz", "molecule", "3\nwater\nO 0 0 0\nH 0.76 0.59 0\nH -0.76 0.59 0\n")
seed("extxyz", "bad_lattice", '1\nLattice="1 0 0 0 1 0 0 0"\nH 0 0 0\n')
seed("lammps_data", "triclinic", "two atoms\n\n2 atoms\n1 atom types\n0 2 xlo xhi\n0 2 ylo yhi\n0 3 zlo zhi\n"
     "0.5 0 0 xy xz yz\n\nMasses\n\n1 28.0\n\nAtoms # atomic\n\n2 1 1.0 1.0 1.0\n1 1 0.1 0.2 0.3\n")
seed("lammps_data", "full_style", "water\n\n1 atoms\n0 5 xlo xhi\n0 5 ylo yhi\n0 5 zlo zhi\n\n"
     "Atoms # full\n\n1 1 1 -0.8 1 1 1 0 0 0\n")
seed("lammps_data", "missing_atoms", "x\n\n2 atoms\n0 2 xlo xhi\n0 2 ylo yhi\n0 2 zlo zhi\n\nAtoms # atomic\n\n1 1 0 0 0\n")

rectangle = {"type": "rectangle", "normal": [0, 1, 0], "lower_left_corner": [1.5, 1.5, 0.5],
             "bottom_unit_vector": [1, 0, 0], "bottom_length": 2, "side_length": 2}
disk = {"type": "disk", "center": [2, 2, 2], "normal": [1, 1, 0], "radius": 1.2}
seed("bond_filters", "rectangle", json.dumps([rectangle]))
seed("bond_filters", "disk", json.dumps([disk]))
seed("bond_filters", "both", json.dumps([rectangle, disk], indent=1))
seed("bond_filters", "empty", "[]")

offsets = np.array([0, 2, 3, 3], dtype=np.int64)
indices = np.array([1, 2, 0], dtype=np.int32)
for half in (0, 1):
    for name, off, ind in (("i8_i4", offsets, indices), ("i4_i8", offsets.astype(np.int32), indices.astype(np.int64))):
        a, b = npy(off), npy(ind)
        seed("neighbor_list", f"npy_{name}_half{half}", bytes([half, 3]) + struct.pack("<H", len(a)) + a + b)
    seed("neighbor_list", f"csv_half{half}", bytes([2 | half, 3]) + b"i,j\n0,1\n0,2\n1,0\n")
