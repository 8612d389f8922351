// All cores of one node: the serial algorithm with every phase on all threads — bounds, cell
// sort and coordinate copy, the family pass over runs of cells handed out dynamically, the
// offset scan and the placement of rows.
#include <omp.h>

#include "../core/family_search.hpp"
#include "backends.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon::detail {

bool openmp_built() { return true; }

NeighborList search_openmp(PointView points, const SearchOptions& options, SearchStats& stats, Images images) {
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  Stopwatch clock;
  const Grid grid = Grid::fit(points, images.points, options.horizon, options.cells_per_horizon, threads);
  const CellIndex index(points, grid, threads, images);
  stats.grid_seconds = clock.lap();

  NeighborList list = search_families(index, options, threads);
  stats.search_seconds = clock.lap();
  stats.backend = Backend::openmp;
  stats.threads = threads;
  return list;
}

}  // namespace horizon::detail
