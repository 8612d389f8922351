// All cores of one node: the serial algorithm over many runs of cells at once. Runs hold about
// equal numbers of points and are handed out dynamically, so dense regions do not serialise.
#include <omp.h>

#include <numeric>

#include "../core/family_search.hpp"
#include "backends.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon::detail {

bool openmp_built() { return true; }

namespace {

std::vector<CellRun> split_into_runs(const CellIndex& index, int threads) {
  const std::size_t cells = index.occupied_cells();
  const std::size_t wanted = static_cast<std::size_t>(threads) * 16;
  const std::size_t points_per_run = std::max<std::size_t>(1, index.point_count() / wanted);
  std::vector<CellRun> runs;
  std::size_t first = 0;
  while (first < cells) {
    std::size_t last = first;
    const std::int64_t start = index.points_of(first).begin;
    while (last < cells &&
           static_cast<std::size_t>(index.points_of(last).end - start) < points_per_run)
      ++last;
    last = std::min(cells, std::max(last + 1, first + 1));
    runs.push_back(CellRun{first, last});
    first = last;
  }
  return runs;
}

}  // namespace

NeighborList search_openmp(PointView points, const SearchOptions& options, SearchStats& stats) {
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  Stopwatch clock;
  const CellIndex index(points, Grid::fit(points, options.horizon, options.cells_per_horizon));
  stats.grid_seconds = clock.lap();

  const std::vector<CellRun> runs = split_into_runs(index, threads);
  Buffer<std::int64_t> offsets(points.size() + 1, 0);
  const auto run_count = static_cast<std::int64_t>(runs.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t r = 0; r < run_count; ++r) count_families(index, options, runs[r], offsets.data());

  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  Buffer<point_id> indices(static_cast<std::size_t>(offsets.back()));
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t r = 0; r < run_count; ++r)
    fill_families(index, options, runs[r], offsets.data(), indices.data());
  stats.search_seconds = clock.lap();
  stats.backend = Backend::openmp;
  stats.threads = threads;
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

}  // namespace horizon::detail
