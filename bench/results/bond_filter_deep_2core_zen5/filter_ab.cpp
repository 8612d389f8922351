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
int main(int argc, char** argv) {
  int threads = argc > 1 ? atoi(argv[1]) : 1;
  PointSet points = lattice(100, 3, 10.0);
  SearchOptions o; o.horizon = 0.3015; o.backend = Backend::openmp; o.threads = threads;
  const NeighborList list = search(points.view(), o);
  const std::vector<BondFilter> filters = read_bond_filters("bench/filters/ten_cracks.json");
  std::vector<double> t[2];
  std::size_t kept[2] = {0, 0};
  for (int r = 0; r < 7; ++r)
    for (int mode = 0; mode < 2; ++mode) {
      if (mode) unsetenv("HZ_NO_DEEP"); else setenv("HZ_NO_DEEP", "1", 1);
      NeighborList copy = list;
      auto t0 = std::chrono::steady_clock::now();
      NeighborList f = filter_bonds(std::move(copy), points.view(), filters, o.horizon, threads);
      t[mode].push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      kept[mode] = f.total();
    }
  for (int mode = 0; mode < 2; ++mode) {
    std::sort(t[mode].begin(), t[mode].end());
    printf("%s threads=%d filter min %.1f med %.1f max %.1f ms, kept %zu\n", mode ? "deep shortcut" : "cuts only   ", threads,
           t[mode][0] * 1e3, t[mode][3] * 1e3, t[mode][6] * 1e3, kept[mode]);
  }
}
