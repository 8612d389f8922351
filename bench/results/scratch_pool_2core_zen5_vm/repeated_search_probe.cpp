#include <cstdio>
#include <cstdlib>
#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  double m = atof(argv[1]); int threads = atoi(argv[2]); int periodic = atoi(argv[3]);
  const PointSet points = lattice(100, 3);
  for (int rep = 0; rep < 40; ++rep) {
      SearchOptions o; o.horizon = m * 0.1; o.backend = threads == 1 ? Backend::serial : Backend::openmp; o.threads = threads;
      if (periodic) o.box = {10, 10, 10};
      SearchStats s; Stopwatch w;
      auto l = search(points.view(), o, &s);
      double t = w.lap();
      std::printf("%d total %.4f grid %.4f search %.4f\n", rep, t, s.grid_seconds, s.search_seconds);
  }
}
