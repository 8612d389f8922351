#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>
#include <algorithm>
#include "horizon/bond_filter.hpp"
#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "horizon/io.hpp"
using namespace horizon;
// Same process: the open search (grid + search) and the filter of its list, alternating.
int main(int argc, char** argv) {
  int threads = argc > 1 ? atoi(argv[1]) : 1;
  PointSet points = lattice(100, 3, 10.0);
  SearchOptions o; o.horizon = 0.3015; o.backend = Backend::openmp; o.threads = threads;
  const std::vector<BondFilter> filters = read_bond_filters("/work/main/bench/filters/ten_cracks.json");
  std::vector<double> s, f;
  for (int r = 0; r < 7; ++r) {
    SearchStats stats;
    NeighborList list = search(points.view(), o, &stats);
    s.push_back(stats.grid_seconds + stats.search_seconds);
    auto t0 = std::chrono::steady_clock::now();
    NeighborList kept = filter_bonds(std::move(list), points.view(), filters, o.horizon, threads);
    f.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(s.begin(), s.end()); std::sort(f.begin(), f.end());
  printf("threads=%d search median %.1f ms, filter median %.1f ms, (search + filter) / search %.2f\n", threads, s[3] * 1e3,
         f[3] * 1e3, (s[3] + f[3]) / s[3]);
}
