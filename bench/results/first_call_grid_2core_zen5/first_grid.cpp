#include <chrono>
#include <cstdio>
#include <cstdlib>
#include "horizon/cell_index.hpp"
#include "horizon/generate.hpp"
#include "horizon/buffer.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  int threads = argc > 1 ? atoi(argv[1]) : 1;
  PointSet set = lattice(100, 3, 100.0);
  for (int r = 0; r < 4; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    Grid g = Grid::fit(set.view(), PointView(), 1.5, 1, threads);
    auto t1 = std::chrono::steady_clock::now();
    { CellIndex index(set.view(), g, threads);
    auto t2 = std::chrono::steady_clock::now();
    printf("call %d: fit %.1f ms, index %.1f ms\n", r, std::chrono::duration<double>(t1 - t0).count()*1e3, std::chrono::duration<double>(t2 - t1).count()*1e3); }
    if (argc > 2) release_cached_buffers();
  }
}
