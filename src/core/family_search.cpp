#include "family_search.hpp"

#include <algorithm>
#include <cstring>

#include "memory_check.hpp"
#include "parallel_scan.hpp"

namespace horizon::detail {

namespace {

/// Runs of cells holding about equal numbers of points, 16 per thread, handed out dynamically so
/// dense regions do not serialise.
std::vector<CellRun> split_into_runs(const CellIndex& index, int threads) {
  const std::size_t cells = index.occupied_cells();
  if (threads <= 1) return {CellRun{0, cells}};
  const std::size_t wanted = static_cast<std::size_t>(threads) * 16;
  const std::size_t points_per_run = std::max<std::size_t>(1, index.point_count() / wanted);
  std::vector<CellRun> runs;
  std::size_t first = 0;
  while (first < cells) {
    std::size_t last = first;
    const std::int64_t start = index.points_of(first).begin;
    while (last < cells && static_cast<std::size_t>(index.points_of(last).end - start) < points_per_run) ++last;
    last = std::min(cells, std::max(last + 1, first + 1));
    runs.push_back(CellRun{first, last});
    first = last;
  }
  return runs;
}

}  // namespace

NeighborList search_families(const CellIndex& index, const SearchOptions& options, int threads) {
  const std::size_t n = index.point_count();
  const std::vector<CellRun> runs = split_into_runs(index, threads);
  const auto run_count = static_cast<std::int64_t>(runs.size());

  Buffer<std::int64_t> offsets(n + 1);
  std::memset(offsets.data(), 0, offsets.size() * sizeof(std::int64_t));
  FamilyPass pass{&index, &options, offsets.data(), nullptr};
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
  for (std::int64_t r = 0; r < run_count; ++r) count_families(pass, runs[static_cast<std::size_t>(r)]);

  inclusive_scan(offsets.data(), offsets.size(), threads);
  check_list_fits(offsets.back(), options);
  Buffer<point_id> indices(static_cast<std::size_t>(offsets.back()));
  pass.indices = indices.data();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
  for (std::int64_t r = 0; r < run_count; ++r) fill_families(pass, runs[static_cast<std::size_t>(r)]);
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

}  // namespace horizon::detail
