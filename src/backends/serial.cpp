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

  // 2. Count each family: test every point against the points of its cell's stencil.
  const CellRun all{0, index.occupied_cells()};
  Buffer<std::int64_t> offsets(points.size() + 1, 0);
  count_families(index, options, all, offsets.data());

  // 3. Family sizes become row offsets; a second pass writes each row in its place.
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  Buffer<point_id> indices(static_cast<std::size_t>(offsets.back()));
  fill_families(index, options, all, offsets.data(), indices.data());
  stats.search_seconds = clock.lap();
  stats.backend = Backend::serial;
  stats.threads = 1;
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

}  // namespace horizon::detail
