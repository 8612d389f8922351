#pragma once
// The search step shared by the CPU backends, in two passes over runs of occupied cells: count
// each family, scan the counts into row offsets, then fill each row in place. Counting first
// means no buffer grows, nothing is copied, nothing is capped, and the list's pages are touched
// once (a one-pass variant that stored rows and copied them spent more in page faults than the
// count pass costs).
//
// Count: for one point set and one horizon each pair is tested once (a point against the points
// after it in its cell and the cell's upper half stencil, a hit counting for both). Threads count
// slabs of whole cell layers (at least k each), cut into bands of lines when a thread would get
// fewer than 8 slabs, in four colours by the parities of slab and band, one colour after another,
// so no two threads write the same counts. Query subsets and per-point radii count each row over
// the stencil cells it reaches. Fill: a cell's points are tested in tiles of 4, 2 or 1 against each
// vector of candidates (a candidate loaded once per tile); found rows wait in a ring of buffers
// (32 KB) and are sorted or copied to their places when it is full, so stores to random places
// (input in no spatial order) do not stall the tests. Rows that fit the sorting network
// (sort_network-inl.h: 128 ids with AVX-512, 64 with AVX2) are sorted in registers; a cell with a
// large stencil and longer rows scans its stencil sorted by id once (sorted_stencil.hpp).
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "horizon/cell_index.hpp"
#include "horizon/neighbor_list.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// Occupied cells [first, last) of a CellIndex.
struct CellRun {
  std::size_t first = 0, last = 0;
};

/// The cells of one slab of layers whose lines lie in one band: a run per layer.
using CellBlock = std::vector<CellRun>;

/// The work of count_each_pair_once() on `threads` threads, in four colours counted one after
/// another: the blocks of a colour write disjoint counts, so they run at once. Slabs of whole
/// layers (at least k each), and when a layer holds more than its share of points (lattice 100,
/// m = 1.5: 67 layers, 34 slabs a parity for 16 threads, of which two threads took a third),
/// bands of lines across them too (3-D, dense grid). An upper stencil reaches k layers up and
/// k lines either side, so bands of at least 2k lines keep the bands two apart disjoint, as
/// slabs of at least k layers do the slabs two apart.
std::array<std::vector<CellBlock>, 4> count_pass_blocks(const CellIndex& index, int threads);

/// What both passes read, and the list they write.
struct FamilyPass {
  const CellIndex* index = nullptr;
  const SearchOptions* options = nullptr;
  std::int64_t* offsets = nullptr;  ///< count: offsets[i + 1] = family size; fill: row offsets
  point_id* indices = nullptr;      ///< fill: the rows
  /// fill: only the rows of points [rows_begin, rows_end), row i at indices + offsets[i] -
  /// indices_base (a batch of a list built in parts).
  point_id rows_begin = 0, rows_end = std::numeric_limits<point_id>::max();
  std::int64_t indices_base = 0;
  /// Per-point radii (radii.hpp), by sorted position (CellIndex::order, read in the order the
  /// passes visit the points): the point at position p has a row of the points within
  /// row_radius[p] (<= the index's horizon), and no row when it is 0. Null: every row within the
  /// horizon.
  const double* row_radius = nullptr;
  /// With row_radius, the min rule: each point's own threshold (metric_threshold of its radius)
  /// by sorted position, padded like the coordinates; a pair is kept only below both its row's
  /// and its candidate's. Such rows never come from the sorted stencil.
  const double* candidate_threshold = nullptr;
  /// fill: when set, row i goes to indices + offsets[i] - indices_base as always, but the
  /// offsets are only room for it (its stencil's size), and its length is written to found[i].
  std::int64_t* found = nullptr;
};

/// For each point i of the run: offsets[i + 1] = the size of its family. Compiled for each SIMD
/// instruction set; the best one this CPU has runs (as for fill_families).
void count_families(const FamilyPass& pass, CellRun run);

/// The same counts with each pair of points tested once, for one point set and one horizon
/// (no per-point radii, query subset or periodic images): counts[p] += the family size of the
/// point at sorted position p, for the points of the run and those after it in the stencil.
void count_each_pair_once(const FamilyPass& pass, CellRun run, std::int64_t* counts);

/// Writes the family of each point i of the run to indices[offsets[i] ...] (offsets scanned),
/// ascending when options.sort_rows.
void fill_families(const FamilyPass& pass, CellRun run);

/// The instruction set the passes run with on this CPU (e.g. "AVX3", "AVX2").
const char* simd_target();

/// The neighbour list of the points of `index` on `threads` threads (1: serially).
NeighborList search_families(const CellIndex& index, const SearchOptions& options, int threads);

/// Per-point radii in classes (radii.hpp): the index at the class's largest radius, and each
/// point's radius by sorted position in it, 0 for the points of other classes.
struct RadiusClass {
  const CellIndex* index = nullptr;
  const double* row_radius = nullptr;
  const double* candidate_threshold = nullptr;  ///< the min rule (FamilyPass::candidate_threshold)
};

/// The list whose row i comes from the class holding point i (exactly one per point): every
/// class counted into one offsets array, then filled into one list, with no parts to join.
NeighborList search_radius_classes(std::span<const RadiusClass> classes, const SearchOptions& options, int threads);

/// The same list in batches of whole rows, for lists larger than memory: `begin(offsets)` once
/// the count pass has given every row's offset (N + 1 of them), then `rows(first, last, ids)`
/// for consecutive batches [first, last) of at most `batch_entries` ids (a longer row alone).
/// Each batch fills only the cells holding one of its points.
void search_families_in_batches(const CellIndex& index, const SearchOptions& options, int threads,
                                std::int64_t batch_entries,
                                const std::function<void(const std::int64_t* offsets)>& begin,
                                const std::function<void(std::size_t first, std::size_t last, const point_id* ids)>& rows);

}  // namespace horizon::detail
