// One CellIndex built 21 times (minimum and median): random cloud of 10^6 or lattice 100, the
// horizon 0.15 (m = 1.5 on the lattice). usage: cell_index_bench random|lattice THREADS
#include "horizon/cell_index.hpp"
#include "horizon/generate.hpp"
#include <omp.h>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>
using namespace horizon;
int main(int argc, char** argv) {
  const PointSet points = std::strcmp(argv[1], "random") == 0 ? random_cloud(1000000) : lattice(100);
  const int threads = atoi(argv[2]);
  const Grid grid = Grid::fit(points.view(), PointView(), 0.15, 1, threads);
  std::vector<double> t;
  for (int r = 0; r < 21; ++r) { double s = omp_get_wtime(); CellIndex index(points.view(), grid, threads); t.push_back(1e3 * (omp_get_wtime() - s)); }
  std::sort(t.begin(), t.end());
  std::printf("%s %s t=%d min %.2f med %.2f ms\n", argv[0], argv[1], threads, t[0], t[10]);
}
