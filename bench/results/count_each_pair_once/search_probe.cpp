#include <cstdio>
#include <cstdlib>
#include <string>
#include <algorithm>
#include "horizon/generate.hpp"
#include "horizon/stopwatch.hpp"
#include "horizon/search.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  std::string kind = argv[1]; double m = std::atof(argv[2]); int threads = std::atoi(argv[3]); int reps = std::atoi(argv[4]);
  PointSet points = kind == "lattice" ? lattice(100, 3) : random_cloud(1000000, 3, 1);
  SearchOptions o; o.horizon = m * 0.1; o.backend = threads == 1 ? Backend::serial : Backend::openmp; o.threads = threads;
  if (argc > 5) o.half = true;
  NeighborList l;
  double best = 1e9; for (int k = 0; k < reps; ++k) { Stopwatch c; l = search(points.view(), o); best = std::min(best, c.lap()); } std::fprintf(stderr, "best %.4f ", best);
  std::fprintf(stderr, "entries %lld\n", (long long)l.total());
}
