#pragma once
// The search step shared by the CPU backends, in two passes over runs of occupied cells: count
// each family, scan the counts into row offsets, then fill each row in place. Counting first
// means no buffer grows, nothing is copied, nothing is capped, and the list's pages are touched
// once (a one-pass variant that stored rows and copied them spent more in page faults than the
// count pass costs).
#include <cstdint>

#include "horizon/cell_index.hpp"
#include "horizon/neighbor_list.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// Occupied cells [first, last) of a CellIndex.
struct CellRun {
  std::size_t first = 0, last = 0;
};

/// What both passes read, and the list they write.
struct FamilyPass {
  const CellIndex* index = nullptr;
  const SearchOptions* options = nullptr;
  std::int64_t* offsets = nullptr;  ///< count: offsets[i + 1] = family size; fill: row offsets
  point_id* indices = nullptr;      ///< fill: the rows
};

/// For each point i of the run: offsets[i + 1] = the size of its family. Compiled for each SIMD
/// instruction set; the best one this CPU has runs (as for fill_families).
void count_families(const FamilyPass& pass, CellRun run);

/// Writes the family of each point i of the run to indices[offsets[i] ...] (offsets scanned),
/// ascending when options.sort_rows.
void fill_families(const FamilyPass& pass, CellRun run);

/// The instruction set the passes run with on this CPU (e.g. "AVX3", "AVX2").
const char* simd_target();

/// The neighbour list of the points of `index` on `threads` threads (1: serially).
NeighborList search_families(const CellIndex& index, const SearchOptions& options, int threads);

}  // namespace horizon::detail
