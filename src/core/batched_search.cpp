#include "horizon/batched_search.hpp"

#include <omp.h>

#include "../backends/backends.hpp"
#include "family_search.hpp"
#include "reference_search.hpp"
#include "horizon/error.hpp"
#include "horizon/grid.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon {

void search_in_batches(PointView points, const SearchOptions& options, std::int64_t batch_entries,
                       const RowBatchSink& sink, SearchStats* stats) {
  detail::validate_search(points, options);
  if (options.backend == Backend::cuda || !options.devices.empty())
    throw Error("a list in batches is built on the CPU backends (serial, openmp), not cuda");
  if (detail::is_periodic(options)) throw Error("a list in batches is not built for a periodic box");
  SearchStats local;
  SearchStats& out = stats ? *stats : local;
  out = SearchStats{};
  if (points.empty()) {
    const std::int64_t offsets[1] = {0};
    sink.begin(offsets, 0);
    return;
  }
  const bool serial = options.backend == Backend::serial;
  const int threads = serial ? 1 : options.threads > 0 ? options.threads : omp_get_max_threads();
  Stopwatch clock;
  const CellIndex index(points, Grid::fit(points, options.horizon, options.cells_per_horizon, threads), threads);
  out.grid_seconds = clock.lap();
  detail::search_families_in_batches(
      index, options, threads, batch_entries, [&](const std::int64_t* offsets) { sink.begin(offsets, points.size()); },
      sink.rows);
  out.search_seconds = clock.lap();
  out.backend = serial ? Backend::serial : Backend::openmp;
  out.threads = threads;
}

}  // namespace horizon
