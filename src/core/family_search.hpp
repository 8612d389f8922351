#pragma once
// The search step shared by the CPU backends, in two passes over runs of occupied cells, as
// the GPU backend does it: count each family, scan the counts into row offsets, then fill each
// row in place. Counting first means no buffer grows, nothing is copied, and nothing is capped.
#include <cstdint>

#include "horizon/cell_index.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// Occupied cells [first, last) of a CellIndex.
struct CellRun {
  std::size_t first = 0, last = 0;
};

/// For each point i of the run: offsets[i + 1] = the size of its family.
void count_families(const CellIndex& index, const SearchOptions& options, CellRun run,
                    std::int64_t* offsets);

/// Writes the family of each point i of the run to indices[offsets[i] ...] (offsets scanned),
/// sorted ascending when options.sort_rows.
void fill_families(const CellIndex& index, const SearchOptions& options, CellRun run,
                   const std::int64_t* offsets, point_id* indices);

}  // namespace horizon::detail
