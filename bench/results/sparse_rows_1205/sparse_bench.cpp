// Sparse grids (bench/results/sparse_rows_1205): DESIGN.md's clustered cloud of 10^6 points at
// m = 1.5 (horizon 0.249: 66.8 entries a point), with and without one far outlier (a point at
// (1000, 1000, 1000) makes the grid sparse), k = 1..3, one thread and all; then per-point radii
// (log-uniform over 10x around 0.15, gather), whose small class's grid is sparse at k = 2.
// Median of 3 of grid + search. Built against a libhorizon.a: see run.sh.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/grid.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"

using namespace horizon;

template <class Run>
double median_seconds(Run run) {
  std::vector<double> s;
  for (int rep = 0; rep < 3; ++rep) {
    const SearchStats stats = run();
    s.push_back(stats.grid_seconds + stats.search_seconds);
  }
  std::sort(s.begin(), s.end());
  return s[1];
}

int main() {
  PointSet points = clustered_cloud(1000000, 64, 1.0, 3, 2);
  std::printf("case,k,threads,dense,seconds\n");
  for (const bool outlier : {false, true}) {
    if (outlier) points.xyz.insert(points.xyz.end(), {1000.0, 1000.0, 1000.0});
    for (int k = 1; k <= 3; ++k)
      for (const int threads : {1, omp_get_max_threads()}) {
        SearchOptions options;
        options.horizon = 0.249215;
        options.cells_per_horizon = k;
        options.backend = Backend::openmp;
        options.threads = threads;
        const bool dense = Grid::fit(points.view(), options.horizon, k).dense;
        const double s = median_seconds([&] {
          SearchStats stats;
          search(points.view(), options, &stats);
          return stats;
        });
        std::printf("%s,%d,%d,%d,%.3f\n", outlier ? "outlier" : "clustered", k, threads, dense, s);
      }
  }
  points.xyz.resize(points.xyz.size() - 3);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> exponent(-0.5 * std::log(10.0), 0.5 * std::log(10.0));
  std::vector<double> radii(points.size());
  for (double& r : radii) r = 0.15 * std::exp(exponent(rng));
  for (int k = 1; k <= 2; ++k)
    for (const int threads : {1, omp_get_max_threads()}) {
      SearchOptions options;
      options.cells_per_horizon = k;
      options.backend = Backend::openmp;
      options.threads = threads;
      const double s = median_seconds([&] {
        SearchStats stats;
        search_with_radii(points.view(), radii, RadiusRule::gather, options, &stats);
        return stats;
      });
      std::printf("radii_gather,%d,%d,-,%.3f\n", k, threads, s);
    }
}
