// horizon_periodic_bench: what a periodic box costs a repeated search (a solver's every step):
// the lattice filling [0, 10)^3 searched open and with every axis periodic, in one process, on
// one core, on all and on the GPU when there is one (host arrays in and out); CSV with the
// ratio. (periodic_cost.sh measures first calls via the CLI.)
#include <CLI/CLI.hpp>
#include <omp.h>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "median_seconds.hpp"

using namespace horizon;

/// A call's phases in milliseconds: grid/search, and on the GPU h2d/kernels/d2h too.
std::string phases(const SearchStats& s) {
  char text[160];
  if (s.backend == Backend::cuda)
    std::snprintf(text, sizeof(text), "grid %.1f h2d %.1f kernels %.1f d2h %.1f", 1e3 * s.grid_seconds,
                  1e3 * s.host_to_device_seconds, 1e3 * s.kernel_seconds, 1e3 * s.device_to_host_seconds);
  else
    std::snprintf(text, sizeof(text), "grid %.1f search %.1f", 1e3 * s.grid_seconds, 1e3 * s.search_seconds);
  return text;
}

int main(int argc, char** argv) {
  CLI::App app{"horizon_periodic_bench: a periodic box against the open one, as CSV"};
  int n = 100, reps = 5;
  app.add_option("--n", n, "lattice points per side");
  app.add_option("--reps", reps, "repetitions (the median is reported)");
  CLI11_PARSE(app, argc, argv);
  std::printf("# %d hardware threads; lattice %d in [0, 10)^3; box 10,10,10 against open; median of %d\n",
              omp_get_max_threads(), n, reps);
  std::printf("m,backend,threads,open_entries,periodic_entries,open_s,periodic_s,periodic_over_open,open_phases,"
              "periodic_phases\n");
  const PointSet points = lattice(n, 3);
  std::vector<std::pair<Backend, int>> runs = {{Backend::serial, 1}, {Backend::openmp, omp_get_max_threads()}};
  if (backend_available(Backend::cuda)) runs.emplace_back(Backend::cuda, 1);
  for (double m : {1.5, 3.015})
    for (const auto& [backend, threads] : runs) {
      SearchOptions open;
      open.horizon = m * 10.0 / n;
      open.backend = backend;
      open.threads = threads;
      SearchOptions periodic = open;
      periodic.box = {10, 10, 10};
      std::int64_t open_entries = 0, periodic_entries = 0;
      SearchStats open_stats, periodic_stats;  // of the last call
      const double open_s =
          median_seconds(reps, [&] { open_entries = search(points.view(), open, &open_stats).total(); });
      const double periodic_s =
          median_seconds(reps, [&] { periodic_entries = search(points.view(), periodic, &periodic_stats).total(); });
      std::printf("%g,%s,%d,%lld,%lld,%.4f,%.4f,%.2f,%s,%s\n", m, backend_name(backend), threads,
                  static_cast<long long>(open_entries), static_cast<long long>(periodic_entries), open_s, periodic_s,
                  periodic_s / open_s, phases(open_stats).c_str(), phases(periodic_stats).c_str());
    }
}
