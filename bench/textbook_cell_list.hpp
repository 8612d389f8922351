#pragma once
// The anchor horizon must beat: a textbook cell list, as a competent programmer writes it in an
// afternoon. Counting sort by cell, coordinates copied in cell order (SoA), the 27-cell stencil
// walked as 9 runs of 3 adjacent cells, a count pass and a fill pass; rows left unsorted.
// Euclidean, 3-D, full list, cell side = horizon. Same semantics as horizon (strict <, no self).
#include <cstdint>
#include <vector>

#include "horizon/buffer.hpp"
#include "horizon/points.hpp"

namespace bench {

struct TextbookList {
  std::vector<std::int64_t> offsets;
  horizon::Buffer<std::int32_t> indices;
  double grid_seconds = 0, search_seconds = 0;
  double candidates_per_point = 0;  ///< distance tests per point (stencil size)
};

/// `threads` > 1 runs the count and fill passes with an OpenMP `parallel for` over cells.
TextbookList textbook_cell_list(const horizon::PointSet& points, double horizon, int threads);

}  // namespace bench
