// horizon_bench: neighbour-list throughput on the benchmark problems of DESIGN.md, with
// nanoflann (a k-d tree, one core) as the anchor measured in the same run. Prints CSV.
#include <CLI/CLI.hpp>
#include <nanoflann.hpp>
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"

namespace {

using namespace horizon;

struct Problem {
  std::string name;
  int n;  // lattice points per side (0 for clouds)
  double m;
  PointSet points;
  double horizon;
};

struct Timing {
  double grid = 0, search = 0, total = 0;
  std::int64_t neighbors = 0;
};

// nanoflann reads the points through this adaptor (no copy).
struct Cloud {
  const PointSet& set;
  std::size_t kdtree_get_point_count() const { return set.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return set.xyz[i * 3 + d]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3>;

// The same output as horizon's: full list, CSR, each family sorted by id.
Timing nanoflann_list(const PointSet& points, double horizon) {
  Stopwatch clock;
  Cloud cloud{points};
  Tree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  Timing t;
  t.grid = clock.lap();
  std::vector<std::int64_t> offsets{0};
  offsets.reserve(points.size() + 1);
  std::vector<point_id> indices;
  std::vector<std::pair<unsigned, double>> found;
  const nanoflann::SearchParams unsorted(32, 0, false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    found.clear();
    tree.radiusSearch(&points.xyz[i * 3], horizon * horizon, found, unsorted);  // squared radius
    const std::size_t first = indices.size();
    for (const auto& [j, d] : found)
      if (j != i) indices.push_back(static_cast<point_id>(j));
    std::sort(indices.begin() + static_cast<std::ptrdiff_t>(first), indices.end());
    offsets.push_back(static_cast<std::int64_t>(indices.size()));
  }
  t.search = clock.lap();
  t.total = t.grid + t.search;
  t.neighbors = offsets.back();
  return t;
}

Timing horizon_list(const PointSet& points, double horizon, Backend backend, int k, int threads) {
  SearchOptions options;
  options.horizon = horizon;
  options.backend = backend;
  options.cells_per_horizon = k;
  options.threads = threads;
  SearchStats stats;
  Stopwatch clock;
  const NeighborList list = search(points.view(), options, &stats);
  return {stats.grid_seconds, stats.search_seconds, clock.lap(), list.total()};
}

// Median of `reps` runs by total time.
Timing median(int reps, const std::function<Timing()>& once) {
  std::vector<Timing> runs;
  for (int r = 0; r < reps; ++r) runs.push_back(once());
  std::sort(runs.begin(), runs.end(), [](const Timing& a, const Timing& b) { return a.total < b.total; });
  return runs[runs.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"horizon_bench: neighbour-list throughput against nanoflann, as CSV"};
  std::vector<int> sizes{37, 47, 53, 59, 63, 80, 100};
  std::vector<double> spacings{1.5, 3.015};
  std::vector<std::string> backends{"serial", "openmp"};
  std::vector<int> ks{1, 2, 3};
  int reps = 3, threads = 0;
  std::size_t cloud_points = 1000000;
  bool anchor = true;
  app.add_option("--sizes", sizes, "lattice points per side")->delimiter(',');
  app.add_option("--m", spacings, "horizons in lattice spacings")->delimiter(',');
  app.add_option("--backends", backends, "backends to time")->delimiter(',');
  app.add_option("--k", ks, "cells per horizon")->delimiter(',');
  app.add_option("--reps", reps, "repetitions (the median is reported)");
  app.add_option("--threads", threads, "openmp threads (0: all)");
  app.add_option("--cloud-points", cloud_points, "points in the random and clustered clouds (0: none)");
  app.add_flag("!--no-anchor", anchor, "skip nanoflann");
  CLI11_PARSE(app, argc, argv);
  if (threads == 0) threads = omp_get_max_threads();

  std::vector<Problem> problems;
  for (int n : sizes)
    for (double m : spacings) problems.push_back({"lattice", n, m, lattice(n), m * 10.0 / n});
  if (cloud_points > 0)
    for (double m : spacings) {
      // Same density as the 10^6-point lattice: spacing h = 10 / cbrt(N).
      const double h = 10.0 / std::cbrt(static_cast<double>(cloud_points));
      problems.push_back({"random", 0, m, random_cloud(cloud_points, 3, 1), m * h});
      problems.push_back({"clustered", 0, m, clustered_cloud(cloud_points, 64, 1.0, 3, 2), m * h});
    }

  std::printf("# machine: %u hardware threads; horizon openmp threads %d; reps %d (median)\n",
              std::thread::hardware_concurrency(), threads, reps);
  std::printf("problem,n,points,m,horizon,backend,k,threads,grid_s,search_s,total_s,points_per_s,neighbors,speedup_vs_nanoflann\n");
  for (const Problem& p : problems) {
    const double n_points = static_cast<double>(p.points.size());
    double anchor_total = 0;
    auto row = [&](const std::string& backend, int k, int used_threads, const Timing& t) {
      std::printf("%s,%d,%zu,%g,%.6g,%s,%d,%d,%.4f,%.4f,%.4f,%.4g,%lld,%.2f\n", p.name.c_str(), p.n,
                  p.points.size(), p.m, p.horizon, backend.c_str(), k, used_threads, t.grid, t.search,
                  t.total, n_points / t.total, static_cast<long long>(t.neighbors),
                  anchor_total > 0 ? anchor_total / t.total : 0.0);
      std::fflush(stdout);
    };
    if (anchor) {
      const Timing t = median(reps, [&] { return nanoflann_list(p.points, p.horizon); });
      anchor_total = t.total;
      row("nanoflann", 0, 1, t);
    }
    for (const std::string& name : backends)
      for (int k : ks) {
        const Backend backend = parse_backend(name);
        const int used = backend == Backend::openmp ? threads : 1;
        row(name, k, used, median(reps, [&] { return horizon_list(p.points, p.horizon, backend, k, used); }));
      }
  }
  return 0;
}
