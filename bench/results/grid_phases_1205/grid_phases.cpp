// Where the grid's time goes at a thread count: the bounds, the whole CellIndex, and inside it
// the (cell, point) keys and their radix sort, each timed alone (minimum and median of REPS).
// usage: grid_phases lattice|random M THREADS REPS
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <functional>
#include <vector>

#include "core/radix_sort.hpp"
#include "horizon/cell_index.hpp"
#include "horizon/generate.hpp"
using namespace horizon;

int main(int argc, char** argv) {
  if (argc != 5) return 2;
  const PointSet points = std::strcmp(argv[1], "random") == 0 ? random_cloud(1000000) : lattice(100);
  const double horizon = atof(argv[2]) * 0.1;
  const int threads = atoi(argv[3]), reps = atoi(argv[4]);
  const auto n = static_cast<std::int64_t>(points.size());
  const Grid grid = Grid::fit(points.view(), PointView(), horizon, 1, threads);
  ScratchBuffer<std::uint64_t> keys(points.size());
  auto make_keys = [&] {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t i = 0; i < n; ++i) {
      const double* p = points.xyz.data() + 3 * i;
      const auto id = grid.linear_id(grid.cell_of(p[0], 0), grid.cell_of(p[1], 1), grid.cell_of(p[2], 2));
      keys[i] = static_cast<std::uint64_t>(id) << 32 | static_cast<std::uint64_t>(i);
    }
  };
  const int bits = std::bit_width(static_cast<std::uint64_t>(grid.cell_count() - 1));
  const std::pair<const char*, std::function<void()>> phases[] = {
      {"bounds", [&] { bounds_of(points.view(), threads); }},
      {"cell_index", [&] { CellIndex index(points.view(), grid, threads); }},
      {"keys", make_keys},
      {"radix", [&] { make_keys(); detail::radix_sort_high_word(keys, bits, threads); }},
  };
  std::printf("%s m=%s threads=%d cells=%lld\n", argv[1], argv[2], threads, static_cast<long long>(grid.cell_count()));
  for (const auto& [name, run] : phases) {
    std::vector<double> seconds;
    for (int r = 0; r < reps; ++r) {
      const double start = omp_get_wtime();
      run();
      seconds.push_back(omp_get_wtime() - start);
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf("  %-10s min %7.3f med %7.3f ms\n", name, 1e3 * seconds[0], 1e3 * seconds[reps / 2]);
  }
}
