// Per-point radii against one radius, grid and search phases apart, at several thread counts.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include "horizon/generate.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::atoi(argv[1]) : 3;
  const PointSet points = clustered_cloud(1000000, 64, 1.0, 3, 2);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> exponent(-0.5 * std::log(10.0), 0.5 * std::log(10.0));
  std::vector<double> radii(points.size());
  for (double& r : radii) r = 0.15 * std::exp(exponent(rng));
  for (int threads : {1, 4, 16}) {
    SearchOptions o; o.backend = threads == 1 ? Backend::serial : Backend::openmp; o.threads = threads;
    SearchOptions one = o; one.horizon = 0.249215;
    for (int r = 0; r < reps; ++r) {
      SearchStats s; Stopwatch c;
      auto l = search_with_radii(points.view(), radii, RadiusRule::gather, o, &s);
      double t = c.lap();
      SearchStats s1; auto l1 = search(points.view(), one, &s1); double t1 = c.lap();
      std::printf("threads %2d radii %.4f s (grid %.4f search %.4f) | single %.4f s (grid %.4f search %.4f) ratio %.2f\n", threads, t, s.grid_seconds, s.search_seconds, t1, s1.grid_seconds, s1.search_seconds, t/t1);
    }
  }
}
