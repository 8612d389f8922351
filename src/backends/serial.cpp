// The reference backend: the fixed-grid search written to be read, on one core.
#include <numeric>

#include "../core/family_search.hpp"
#include "backends.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon::detail {

NeighborList search_serial(PointView points, const SearchOptions& options, SearchStats& stats) {
  Stopwatch clock;
  // 1. Lay the grid over the points and sort them by cell.
  const CellIndex index(points, Grid::fit(points, options.horizon, options.cells_per_horizon));
  stats.grid_seconds = clock.lap();

  // 2. For each occupied cell, test its points against the points of its stencil.
  std::vector<std::int64_t> offsets(points.size() + 1, 0);
  CellRun all{0, index.occupied_cells(), {}};
  find_families(index, options, all, offsets.data());

  // 3. Family sizes become row offsets; rows move to their input-id places, sorted.
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<point_id> indices(static_cast<std::size_t>(offsets.back()));
  place_rows(index, options, all, offsets.data(), indices.data());
  stats.search_seconds = clock.lap();
  stats.backend = Backend::serial;
  stats.threads = 1;
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

}  // namespace horizon::detail
