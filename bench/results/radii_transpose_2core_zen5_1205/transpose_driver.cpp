#include <cmath>
#include <cstdio>
#include <random>
#include "horizon/generate.hpp"
#include "horizon/radii.hpp"
#include "horizon/stopwatch.hpp"
#include "core/transpose_rows.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  int threads = argc > 1 ? atoi(argv[1]) : 1;
  const PointSet points = clustered_cloud(1000000, 64, 1.0, 3, 2);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> exponent(-0.5 * std::log(10.0), 0.5 * std::log(10.0));
  std::vector<double> radii(points.size());
  for (double& r : radii) r = 0.15 * std::exp(exponent(rng));
  SearchOptions o; o.backend = threads == 1 ? Backend::serial : Backend::openmp; o.threads = threads;
  NeighborList g = search_with_radii(points.view(), radii, RadiusRule::gather, o);
  for (int r = 0; r < 5; ++r) {
    Buffer<std::int64_t> off; Buffer<point_id> ids;
    Stopwatch w;
    detail::transpose_rows(g.offsets().data(), g.indices().data(), (std::int64_t)points.size(), threads, off, ids);
    std::printf("transpose %.3f s (%lld entries)\n", w.lap(), (long long)ids.size());
  }
}
