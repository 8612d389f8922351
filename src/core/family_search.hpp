#pragma once
// The search step shared by the CPU backends: find the families of the points of a run of
// occupied cells, then place the rows into the CSR arrays by input id. The serial backend runs
// one run over all cells; the openmp backend many runs in parallel.
#include <cstdint>
#include <memory>
#include <vector>

#include "horizon/cell_index.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// Families of the points in occupied cells [first_cell, last_cell), row after row in sorted
/// position order.
struct CellRun {
  std::size_t first_cell = 0, last_cell = 0;
  std::vector<point_id> ids;  ///< neighbours' input ids
};

/// Fills run.ids and, for each point i of the run, offsets[i + 1] = the size of its family.
void find_families(const CellIndex& index, const SearchOptions& options, CellRun& run,
                   std::int64_t* offsets);

/// Copies the rows of `run` to indices[offsets[i] ...] (offsets now scanned), sorting each row
/// when options.sort_rows.
void place_rows(const CellIndex& index, const SearchOptions& options, const CellRun& run,
                const std::int64_t* offsets, point_id* indices);

}  // namespace horizon::detail
