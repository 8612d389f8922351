// horizon_bench: neighbour-list throughput on the benchmark problems of DESIGN.md against two
// anchors measured in the same process on the same points: a textbook cell list (the same method,
// bench/textbook_cell_list.cpp) on one core and on all cores, and nanoflann's k-d tree (one core).
// Prints CSV with the ratio to the textbook list at the same thread count, and per problem the
// floors: writing the list once at memset speed, and the candidates tested per point.
#include <CLI/CLI.hpp>
#include <nanoflann.hpp>
#include <omp.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"
#include "latency.hpp"
#include "textbook_cell_list.hpp"

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

Timing horizon_list(const PointSet& points, double horizon, Backend backend, int k, int threads,
                    bool sorted) {
  SearchOptions options;
  options.horizon = horizon;
  options.backend = backend;
  options.cells_per_horizon = k;
  options.threads = threads;
  options.sort_rows = sorted;
  SearchStats stats;
  Stopwatch clock;
  const NeighborList list = search(points.view(), options, &stats);
  return {stats.grid_seconds, stats.search_seconds, clock.lap(), list.total()};
}

Timing textbook(const PointSet& points, double horizon, int threads, double* candidates) {
  Stopwatch clock;
  const bench::TextbookList list = bench::textbook_cell_list(points, horizon, threads);
  *candidates = list.candidates_per_point;
  return {list.grid_seconds, list.search_seconds, clock.lap(), list.offsets.back()};
}

// The floor of any list builder: writing the list (offsets and indices) once into fresh memory.
Timing memset_floor(const PointSet& points, std::int64_t entries, int threads) {
  Stopwatch clock;
  Buffer<point_id> indices(static_cast<std::size_t>(entries));
  Buffer<std::int64_t> offsets(points.size() + 1);
  auto* bytes = reinterpret_cast<char*>(indices.data());
  const std::size_t size = indices.size() * sizeof(point_id), piece = std::size_t{1} << 20;
  const auto pieces = static_cast<std::int64_t>((size + piece - 1) / piece);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t i = 0; i < pieces; ++i) {
    const std::size_t at = static_cast<std::size_t>(i) * piece;
    std::memset(bytes + at, 1, std::min(piece, size - at));
  }
  std::memset(offsets.data(), 1, offsets.size() * sizeof(std::int64_t));
  const double seconds = clock.lap();
  return {0, seconds, seconds, entries};
}

// Median of `reps` runs by total time.
Timing median(int reps, const std::function<Timing()>& once) {
  std::vector<Timing> runs;
  for (int r = 0; r < reps; ++r) runs.push_back(once());
  std::sort(runs.begin(), runs.end(), [](const Timing& a, const Timing& b) { return a.total < b.total; });
  return runs[runs.size() / 2];
}

// The same points in a random order: grid methods must not depend on input locality.
PointSet shuffled(const PointSet& points, std::uint64_t seed) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
  PointSet out = points;
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int a = 0; a < 3; ++a) out.xyz[3 * i + a] = points.xyz[3 * order[i] + a];
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"horizon_bench: neighbour-list throughput against a textbook cell list and nanoflann, as CSV"};
  std::vector<int> sizes{37, 47, 53, 59, 63, 80, 100};
  std::vector<double> spacings{1.5, 3.015};
  std::vector<std::string> backends{"serial", "openmp"};
  std::vector<int> ks{1};
  int reps = 3, threads = 0;
  std::size_t cloud_points = 1000000;
  bool nanoflann = false, shuffle = true;
  app.add_option("--sizes", sizes, "lattice points per side")->delimiter(',');
  app.add_option("--m", spacings, "horizons in lattice spacings")->delimiter(',');
  app.add_option("--backends", backends, "backends to time")->delimiter(',');
  app.add_option("--k", ks, "cells per horizon")->delimiter(',');
  app.add_option("--reps", reps, "repetitions (the median is reported)");
  app.add_option("--threads", threads, "openmp threads (0: all)");
  app.add_option("--cloud-points", cloud_points, "points in the random and clustered clouds (0: none)");
  app.add_flag("--nanoflann,!--no-nanoflann", nanoflann, "also time nanoflann (one core; slow)");
  app.add_flag("--shuffled,!--no-shuffled", shuffle, "also time the largest lattice in random order");
  bool latency = false;
  bench::LatencyOptions latency_options;
  app.add_flag("--latency", latency, "instead: the time of one call at small sizes, idle and beside busy processes");
  app.add_option("--latency-sizes", latency_options.sizes, "with --latency: points per call")->delimiter(',');
  app.add_option("--busy", latency_options.busy, "with --latency: busy processes beside the calls (-1: one per hardware thread)")
      ->delimiter(',');
  app.add_option("--seconds", latency_options.seconds, "with --latency: seconds of calls per size, backend and load");
  app.add_option("--block", latency_options.block,
                 "with --latency: calls of one backend in a row, in turn with the others' (1: each call finds the "
                 "caches as the other backends left them)");
  CLI11_PARSE(app, argc, argv);
  if (latency) return bench::run_latency(latency_options);
  if (threads == 0) threads = omp_get_max_threads();

  std::vector<Problem> problems;
  for (int n : sizes)
    for (double m : spacings) problems.push_back({"lattice", n, m, lattice(n), m * 10.0 / n});
  if (shuffle && !sizes.empty()) {
    const int n = *std::max_element(sizes.begin(), sizes.end());
    for (double m : spacings) problems.push_back({"lattice-shuffled", n, m, shuffled(lattice(n), 7), m * 10.0 / n});
  }
  if (cloud_points > 0)
    for (double m : spacings) {
      // Same density as the 10^6-point lattice: spacing h = 10 / cbrt(N).
      const double h = 10.0 / std::cbrt(static_cast<double>(cloud_points));
      problems.push_back({"random", 0, m, random_cloud(cloud_points, 3, 1), m * h});
      problems.push_back({"clustered", 0, m, clustered_cloud(cloud_points, 64, 1.0, 3, 2), m * h});
    }

  std::printf("# machine: %u hardware threads; openmp threads %d; reps %d (median); %s\n",
              std::thread::hardware_concurrency(), threads, reps, cpu_simd_target());
  std::printf("problem,n,points,m,horizon,impl,rows,k,threads,grid_s,search_s,total_s,points_per_s,neighbors,"
              "candidates_per_point,vs_textbook\n");
  for (const Problem& p : problems) {
    const double n_points = static_cast<double>(p.points.size());
    double candidates = 0, textbook_serial = 0, textbook_parallel = 0;
    auto row = [&](const std::string& impl, const char* rows, int k, int used, const Timing& t) {
      const double anchor = used == 1 ? textbook_serial : textbook_parallel;
      std::printf("%s,%d,%zu,%g,%.6g,%s,%s,%d,%d,%.4f,%.4f,%.4f,%.4g,%lld,%.0f,%.2f\n", p.name.c_str(), p.n,
                  p.points.size(), p.m, p.horizon, impl.c_str(), rows, k, used, t.grid, t.search, t.total,
                  n_points / t.total, static_cast<long long>(t.neighbors), candidates,
                  anchor > 0 ? anchor / t.total : 0.0);
      std::fflush(stdout);
    };
    const Timing one = median(reps, [&] { return textbook(p.points, p.horizon, 1, &candidates); });
    row("textbook", "unsorted", 1, 1, one);
    textbook_serial = one.total;
    const Timing all = median(reps, [&] { return textbook(p.points, p.horizon, threads, &candidates); });
    row("textbook", "unsorted", 1, threads, all);
    textbook_parallel = all.total;
    row("floor_memset", "-", 0, 1, median(reps, [&] { return memset_floor(p.points, one.neighbors, 1); }));
    row("floor_memset", "-", 0, threads, median(reps, [&] { return memset_floor(p.points, one.neighbors, threads); }));
    if (nanoflann) row("nanoflann", "sorted", 0, 1, median(reps, [&] { return nanoflann_list(p.points, p.horizon); }));
    for (const std::string& name : backends)
      for (int k : ks)
        for (bool sorted : {true, false}) {
          const Backend backend = parse_backend(name);
          const int used = backend == Backend::openmp ? threads : 1;
          const Timing t = median(reps, [&] { return horizon_list(p.points, p.horizon, backend, k, used, sorted); });
          if (t.neighbors != one.neighbors)
            std::fprintf(stderr, "MISMATCH: %s lists %lld entries, the textbook %lld\n", name.c_str(),
                         static_cast<long long>(t.neighbors), static_cast<long long>(one.neighbors));
          row(name, sorted ? "sorted" : "unsorted", k, used, t);
        }
  }
  return 0;
}
