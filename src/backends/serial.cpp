// The reference backend: the fixed-grid search on one core.
#include "../core/all_pairs_search.hpp"
#include "../core/family_search.hpp"
#include "backends.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon::detail {

NeighborList search_serial(PointView points, const SearchOptions& options, SearchStats& stats, Images images) {
  Stopwatch clock;
  stats.backend = Backend::serial;
  stats.threads = 1;
  if (all_pairs_searchable(points, options, images)) {  // a few points: every pair, no grid
    NeighborList list = search_all_pairs(points, options);
    stats.search_seconds = clock.lap();
    return list;
  }
  // 1. Lay the grid over the points and sort them by cell.
  const CellIndex index(points, Grid::fit(points, images.points, options.horizon, options.cells_per_horizon), 1,
                        images);
  stats.grid_seconds = clock.lap();

  // 2. Test every point against the points of its cell's stencil; rows by input id.
  NeighborList list = search_families(index, options, 1);
  stats.search_seconds = clock.lap();
  return list;
}

}  // namespace horizon::detail
