#pragma once
/// \file cell.hpp
/// Periodic cells of any shape, as atomistic codes (ASE, LAMMPS, vesin) describe them, and the
/// per-entry geometry a search can return beside the ids.
#include <array>

namespace horizon {

/// A simulation cell: its rows are the cell vectors a, b, c (Cartesian), and pbc[k] makes the
/// cell periodic along vector k. Any shape: triclinic, hexagonal, rotated. A vector of zero
/// length is allowed on an open axis (a slab's or a molecule's cell); horizon completes it. A
/// periodic cell must be right-handed (det > 0) and not nearly singular. 2-D points use the
/// upper-left 2 x 2 block and pbc[0..1].
struct Cell {
  std::array<std::array<double, 3>, 3> vectors{};
  std::array<bool, 3> pbc{false, false, false};

  bool periodic() const { return pbc[0] || pbc[1] || pbc[2]; }
  /// An orthorhombic cell with edges `lengths` along x, y, z; an edge of 0 is an open axis.
  static Cell orthorhombic(std::array<double, 3> lengths) {
    Cell cell;
    for (int a = 0; a < 3; ++a) {
      cell.vectors[a][a] = lengths[a];
      cell.pbc[a] = lengths[a] > 0;
    }
    return cell;
  }
};

/// Per-entry arrays a search can compute in the pass that keeps each pair, stored beside the
/// ids (NeighborList::shifts(), distances(), vectors()). For entry (i, j, S): the shift S
/// (integers, one per dimension) says which periodic image of j, the vector is
/// D = x_j + S . cell - x_i and the distance |D|.
struct PairOutputs {
  bool shifts = false;
  bool distances = false;
  bool vectors = false;
  bool any() const { return shifts || distances || vectors; }
  friend bool operator==(const PairOutputs&, const PairOutputs&) = default;
};

}  // namespace horizon
