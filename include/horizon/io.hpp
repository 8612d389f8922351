#pragma once
/// \file io.hpp
/// Reading points and writing neighbour lists. Every writer writes a temporary file beside the
/// target and renames it, so a failure never leaves a truncated file that looks valid. Every
/// reader error names the file and, for text, the line.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "horizon/cell.hpp"
#include "horizon/neighbor_list.hpp"
#include "horizon/points.hpp"
#include "horizon/search.hpp"

namespace horizon {

/// Points from `path`, by extension: `.npy` (N x 2 or N x 3, little-endian float32/float64),
/// else text: one point per line, `x y [z]` separated by commas or spaces, `#` comments, an
/// optional header line; or Peridigm's discretization `x y z block_id volume` (5 columns).
PointSet read_points(const std::string& path);

/// An atomistic system: its atoms' positions and its periodic cell (cell.hpp).
struct Structure {
  PointSet points;
  Cell cell;
};

/// Whether read_structure reads `path`: `.extxyz`, `.xyz` whose first line is the atom count
/// alone, and LAMMPS data files (`.data`, `.lmp`, `data.*`).
bool is_structure_file(const std::string& path);

/// An extended XYZ file of one frame (ASE's: the count, a comment line with Lattice="ax ay az
/// bx by bz cx cy cz", pbc="T T F" and Properties=species:S:1:pos:R:3..., one line per atom;
/// pbc defaults to T T T with a Lattice, F F F without), or a LAMMPS data file (the header's
/// "N atoms", "xlo xhi", ..., "xy xz yz"; the Atoms section of the atomic, charge, molecular,
/// bond, angle or full style, named after "Atoms #"; point k is the atom of the k-th smallest
/// id; image flags are ignored; all three axes periodic, LAMMPS's default boundary). Errors
/// name the file, the line and the key.
Structure read_structure(const std::string& path);

/// A block id per point (Peridigm's blocks, block_filter.hpp): `.npy` of int32/int64 (N), or
/// text with one integer per line. Error naming the file (and line) unless there are `points`
/// ids from 0 to 2^31 - 1.
std::vector<std::int32_t> read_blocks(const std::string& path, std::size_t points);

/// A radius per point (radii.hpp): `.npy` of float64/float32 (N), or text with one number per
/// line. Error naming the file (and line) unless there are `points` numbers; their values are
/// checked by the search (naming the point).
std::vector<double> read_radii(const std::string& path, std::size_t points, const std::string& rows = "points");

/// Points to `.npy` (N x dims float64) or, for any other extension, text `x y [z]` lines.
void write_points(const std::string& path, const PointSet& points);

enum class ListFormat { npy, csv };

/// npy: PREFIX.offsets.npy (int64, N+1) and PREFIX.indices.npy (int32), and the geometry the
/// list carries: PREFIX.shifts.npy (int32, M x dims), PREFIX.distances.npy (float64, M),
/// PREFIX.vectors.npy (float64, M x dims); csv: PREFIX.csv with one `i,j` row per entry (no
/// geometry). Returns the paths written, comma-separated.
std::string write_neighbor_list(const std::string& prefix, const NeighborList& list,
                                ListFormat format);

/// The list of search(points, options) written as write_neighbor_list(prefix, list, npy) writes
/// it, without holding it in memory: built by search_in_batches (batched_search.hpp), at most
/// `batch_entries` ids at a time, each batch appended to the indices file. Refused before
/// anything is written when the files would not fit on their disk. Returns the entries written.
std::int64_t write_neighbor_list_in_batches(const std::string& prefix, PointView points, const SearchOptions& options,
                                           std::int64_t batch_entries, SearchStats* stats = nullptr);

/// Reads what write_neighbor_list wrote (either format; int32 or int64 indices). The number of
/// points is needed for csv, whose rows do not record points with no neighbours.
NeighborList read_neighbor_list(const std::string& prefix, std::size_t points, bool half);

/// Most bonds write_vtk draws as lines.
inline constexpr std::uint64_t max_vtk_bonds = 10'000'000;

/// ParaView output (VTK XML UnstructuredGrid, `.vtu`, little-endian binary): every point as a
/// vertex cell with its family size as point data ("family_size") and, when `points.blocks` is
/// given, its block ("block"), and its radius ("radius") when `radii` are; with `bonds`, every
/// pair also as a line cell (refused above max_vtk_bonds). 2-D points get z = 0.
void write_vtk(const std::string& path, const PointSet& points, const NeighborList& list, bool bonds,
               std::span<const double> radii = {});

}  // namespace horizon
