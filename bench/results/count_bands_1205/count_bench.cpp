// The count pass alone (count_each_pair_once over every cell), in one process, alternating:
// the four-colour blocks of count_pass_blocks() against slabs of layers only, two parities
// (the code before). usage: count_bench lattice|random M THREADS REPS
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/family_search.hpp"
#include "horizon/generate.hpp"
#include "horizon/grid.hpp"
using namespace horizon;
using namespace horizon::detail;

// Copy of split_into_slabs (family_search.cpp): the blocks before bands.
static std::array<std::vector<CellBlock>, 4> slabs_only(const CellIndex& index, int threads) {
  const std::size_t cells = index.occupied_cells();
  const std::int64_t k = index.grid().cells_per_horizon;
  const std::size_t per = std::max<std::size_t>(1, index.point_count() / (static_cast<std::size_t>(threads) * 8));
  std::array<std::vector<CellBlock>, 4> colours;
  std::size_t first = 0, slab = 0;
  for (std::size_t c = 1; c <= cells; ++c)
    if (c == cells || (index.layer(c) != index.layer(c - 1) && index.layer(c) - index.layer(first) >= k &&
                       static_cast<std::size_t>(index.points_of(c).begin - index.points_of(first).begin) >= per)) {
      colours[slab++ % 2].push_back({CellRun{first, c}});
      first = c;
    }
  return colours;
}

static double count_pass(const FamilyPass& pass, const std::array<std::vector<CellBlock>, 4>& colours,
                         std::vector<std::int64_t>& counts, int threads) {
  std::fill(counts.begin(), counts.end(), 0);
  const double start = omp_get_wtime();
  for (const auto& colour : colours) {
    const auto n = static_cast<std::int64_t>(colour.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::int64_t b = 0; b < n; ++b)
      for (const CellRun run : colour[static_cast<std::size_t>(b)]) count_each_pair_once(pass, run, counts.data());
  }
  return omp_get_wtime() - start;
}

int main(int argc, char** argv) {
  if (argc != 5) return 2;
  const bool random = std::strcmp(argv[1], "random") == 0;
  const double m = atof(argv[2]);
  const int threads = atoi(argv[3]), reps = atoi(argv[4]);
  const PointSet points = random ? random_cloud(1000000) : lattice(100);
  SearchOptions options;
  options.horizon = m * 0.1;
  const Grid grid = Grid::fit(points.view(), options.horizon, 1);
  const CellIndex index(points.view(), grid, threads);
  FamilyPass pass{&index, &options};
  const auto bands = count_pass_blocks(index, threads), slabs = slabs_only(index, threads);
  std::vector<std::int64_t> counts(index.point_count() + CellIndex::padding), reference;
  std::vector<double> with_bands, with_slabs;
  for (int r = 0; r < reps; ++r) {
    with_slabs.push_back(count_pass(pass, slabs, counts, threads));
    reference = counts;
    with_bands.push_back(count_pass(pass, bands, counts, threads));
    if (counts != reference) return std::puts("counts differ"), 1;
  }
  auto blocks = [](const auto& colours) {
    std::string s;
    for (const auto& colour : colours) s += std::to_string(colour.size()) + " ";
    return s;
  };
  std::sort(with_bands.begin(), with_bands.end());
  std::sort(with_slabs.begin(), with_slabs.end());
  std::printf("%s m=%g threads=%d blocks per colour: bands %s| slabs %s\n", argv[1], m, threads,
              blocks(bands).c_str(), blocks(slabs).c_str());
  std::printf("  bands min %.3f med %.3f ms   slabs min %.3f med %.3f ms\n", 1e3 * with_bands[0],
              1e3 * with_bands[reps / 2], 1e3 * with_slabs[0], 1e3 * with_slabs[reps / 2]);
}
