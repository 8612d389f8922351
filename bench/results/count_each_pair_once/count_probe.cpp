#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include <algorithm>
#include "horizon/generate.hpp"
#include "horizon/stopwatch.hpp"
#include "horizon/search.hpp"
#include "horizon/cell_index.hpp"
#include "core/family_search.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  std::string kind = argv[1]; double m = std::atof(argv[2]); int reps = std::atoi(argv[3]);
  PointSet points = kind == "lattice" ? lattice(100, 3) : kind == "random" ? random_cloud(1000000, 3, 1) : clustered_cloud(1000000, 64, 0.5);
  SearchOptions o; o.horizon = m * 0.1; o.half = argc > 4;
  Grid grid = Grid::fit(points.view(), o.horizon, 1);
  CellIndex index(points.view(), grid, 1);
  std::vector<std::int64_t> offsets(points.size() + 1);
  std::vector<std::int64_t> counts(points.size() + 16);
  detail::FamilyPass pass{&index, &o};
  pass.offsets = offsets.data();
  double best_old = 1e9, best_new = 1e9;
  for (int k = 0; k < reps; ++k) {
    std::fill(offsets.begin(), offsets.end(), 0);
    Stopwatch c; detail::count_families(pass, detail::CellRun{0, index.occupied_cells()}); best_old = std::min(best_old, c.lap());
    std::fill(counts.begin(), counts.end(), 0);
    Stopwatch c2; detail::count_each_pair_once(pass, detail::CellRun{0, index.occupied_cells()}, counts.data()); best_new = std::min(best_new, c2.lap());
  }
  long long bad = 0;
  for (std::size_t p = 0; p < points.size(); ++p) bad += offsets[index.order()[p] + 1] != counts[p];
  std::printf("%s m=%g half=%d: count_families %.4f s, each pair once %.4f s, ratio %.2f, mismatches %lld\n", kind.c_str(), m, (int)o.half, best_old, best_new, best_old / best_new, bad);
}
