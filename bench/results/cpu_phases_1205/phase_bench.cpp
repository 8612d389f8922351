// Phases of the CPU search (grid, count pass, offsets, scan, list allocation, fill) at a thread
// count: where does 16-thread scaling go? usage: phase_bench lattice|shuffled|random M THREADS REPS
// (shuffled: the lattice in a random order, as horizon_bench --shuffled)
#include <omp.h>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>
#include "core/family_search.hpp"
#include "core/parallel_scan.hpp"
#include "horizon/generate.hpp"
#include "horizon/grid.hpp"
#include <hwy/targets.h>
#include <numeric>
#include <random>
using namespace horizon;
using namespace horizon::detail;

static std::vector<CellRun> slabs_of(const CellIndex& index, int threads) {  // copy of split_into_slabs
  const std::size_t cells = index.occupied_cells();
  const std::int64_t k = index.grid().cells_per_horizon;
  const std::size_t per = std::max<std::size_t>(1, index.point_count() / (static_cast<std::size_t>(threads) * 8));
  std::vector<CellRun> slabs;
  std::size_t first = 0;
  for (std::size_t c = 1; c < cells; ++c)
    if (index.layer(c) != index.layer(c - 1) && index.layer(c) - index.layer(first) >= k &&
        static_cast<std::size_t>(index.points_of(c).begin - index.points_of(first).begin) >= per) {
      slabs.push_back(CellRun{first, c});
      first = c;
    }
  if (first < cells) slabs.push_back(CellRun{first, cells});
  return slabs;
}
static std::vector<CellRun> runs_of(const CellIndex& index, int threads) {  // copy of split_into_runs
  const std::size_t cells = index.occupied_cells();
  if (threads <= 1) return {CellRun{0, cells}};
  const std::size_t per = std::max<std::size_t>(1, index.point_count() / (static_cast<std::size_t>(threads) * 16));
  std::vector<CellRun> runs;
  std::size_t first = 0;
  while (first < cells) {
    std::size_t last = first;
    const std::int64_t start = index.points_of(first).begin;
    while (last < cells && static_cast<std::size_t>(index.points_of(last).end - start) < per) ++last;
    last = std::min(cells, std::max(last + 1, first + 1));
    runs.push_back(CellRun{first, last});
    first = last;
  }
  return runs;
}

int main(int argc, char** argv) {
  const bool random = std::strcmp(argv[1], "random") == 0;
  const double m = atof(argv[2]);
  const int threads = atoi(argv[3]), reps = atoi(argv[4]);
  PointSet p = random ? random_cloud(1000000) : lattice(100);
  if (std::strcmp(argv[1], "shuffled") == 0) {
    std::vector<std::size_t> order(p.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(7));
    const PointSet in_order = p;
    for (std::size_t i = 0; i < order.size(); ++i)
      for (int a = 0; a < 3; ++a) p.xyz[3 * i + a] = in_order.xyz[3 * order[i] + a];
  }
  SearchOptions options;
  options.horizon = m * 0.1;
  options.sort_rows = getenv("UNSORTED") == nullptr;
  options.half = getenv("HALF") != nullptr;
  if (getenv("AVX2")) hwy::SetSupportedTargetsForTest(HWY_AVX2);
  const char* names[] = {"grid", "zero", "count0", "count1", "place", "scan", "alloc", "fill", "count_rows_all"};
  std::vector<std::vector<double>> t(9);
  long long entries = 0;
  for (int r = 0; r < reps; ++r) {
    double c0 = omp_get_wtime();
    const Grid grid = Grid::fit(p.view(), {}, options.horizon, options.cells_per_horizon, threads);
    const CellIndex index(p.view(), grid, threads, {});
    double c1 = omp_get_wtime(); t[0].push_back(c1 - c0);
    const std::vector<CellRun> runs = runs_of(index, threads);
    FamilyPass pass{&index, &options};
    Buffer<std::int64_t> offsets(index.row_count() + 1);
    offsets[0] = 0;
    pass.offsets = offsets.data();
    ScratchBuffer<std::int64_t> counts(index.point_count() + CellIndex::padding);
    c0 = omp_get_wtime();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
    for (std::int64_t q = 0; q < static_cast<std::int64_t>(counts.size()); ++q) counts[q] = 0;
    c1 = omp_get_wtime(); t[1].push_back(c1 - c0);
    const std::vector<CellRun> slabs = slabs_of(index, threads);
    const auto slab_count = static_cast<std::int64_t>(slabs.size());
    for (std::int64_t parity = 0; parity < 2; ++parity) {
      c0 = omp_get_wtime();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
      for (std::int64_t s = parity; s < slab_count; s += 2) count_each_pair_once(pass, slabs[s], counts.data());
      c1 = omp_get_wtime(); t[2 + parity].push_back(c1 - c0);
    }
    c0 = omp_get_wtime();
    const point_id* order = index.order().data();
    const auto cells = static_cast<std::int64_t>(index.occupied_cells());
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
    for (std::int64_t c = 0; c < cells; ++c) {
      const auto [first, last] = index.rows_of(c);
      for (std::int64_t q = first; q < last; ++q) offsets[order[q] + 1] = counts[q];
    }
    c1 = omp_get_wtime(); t[4].push_back(c1 - c0);
    inclusive_scan(offsets.data(), offsets.size(), threads);
    c0 = omp_get_wtime(); t[5].push_back(c0 - c1);
    Buffer<point_id> indices(static_cast<std::size_t>(offsets.back()));
    pass.indices = indices.data();
    c1 = omp_get_wtime(); t[6].push_back(c1 - c0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
    for (std::int64_t r2 = 0; r2 < static_cast<std::int64_t>(runs.size()); ++r2) fill_families(pass, runs[r2]);
    c0 = omp_get_wtime(); t[7].push_back(c0 - c1);
    entries = offsets.back();
    // the count over every row's whole stencil (no parity barrier), for comparison
    std::memset(offsets.data(), 0, offsets.size() * sizeof(std::int64_t));
    c0 = omp_get_wtime();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
    for (std::int64_t r2 = 0; r2 < static_cast<std::int64_t>(runs.size()); ++r2) count_families(pass, runs[r2]);
    c1 = omp_get_wtime(); t[8].push_back(c1 - c0);
    if (r == 0) std::printf("slabs %lld runs %zu\n", (long long)slab_count, runs.size());
  }
  std::printf("%s m=%g threads=%d entries=%lld (%s)\n", argv[1], m, threads, entries, simd_target());
  for (int i = 0; i < 9; ++i) {
    std::sort(t[i].begin(), t[i].end());
    std::printf("  %-15s min %8.3f med %8.3f ms\n", names[i], t[i][0] * 1e3, t[i][t[i].size() / 2] * 1e3);
  }
}
