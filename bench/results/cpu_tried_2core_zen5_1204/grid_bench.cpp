#include <chrono>
#include <cstdio>
#include <algorithm>
#include <vector>
#include "horizon/cell_index.hpp"
#include "horizon/generate.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  int threads = argc > 1 ? atoi(argv[1]) : 1;
  PointSet sets[2] = {lattice(100), random_cloud(1000000)};
  const char* names[2] = {"lattice", "random"};
  for (int s = 0; s < 2; ++s) for (double h : {0.15, 0.3015}) {
    std::vector<double> t;
    for (int r = 0; r < 9; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      Grid g = Grid::fit(sets[s].view(), PointView(), h, 1, threads);
      CellIndex index(sets[s].view(), g, threads);
      t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(t.begin(), t.end());
    printf("%s h=%g threads=%d grid min %.1f med %.1f ms\n", names[s], h, threads, t[0]*1e3, t[4]*1e3);
  }
}
