// horizon_verlet_bench: a Verlet list's refresh() against a fresh search of the same moved
// points (lattice n, m = 1.5 and 3.015, skin = 0.1 horizon, every point moved by up to a fifth
// of the skin), checked equal, on one core and on all; CSV with the ratio.
#include <CLI/CLI.hpp>
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/stopwatch.hpp"
#include "horizon/verlet_list.hpp"
#include "median_seconds.hpp"

using namespace horizon;

int main(int argc, char** argv) {
  CLI::App app{"horizon_verlet_bench: Verlet refresh against a fresh search, as CSV"};
  int n = 100, reps = 3;
  double skin_fraction = 0.1;
  app.add_option("--n", n, "lattice points per side");
  app.add_option("--reps", reps, "repetitions (the median is reported)");
  app.add_option("--skin", skin_fraction, "skin as a fraction of the horizon");
  CLI11_PARSE(app, argc, argv);
  std::printf("# %d hardware threads; lattice %d, skin %.3g horizon, points moved by up to skin / 5\n",
              omp_get_max_threads(), n, skin_fraction);
  std::printf("m,threads,entries,candidates,build_s,fresh_search_s,refresh_s,needs_rebuild_s,fresh_over_refresh\n");
  const PointSet points = lattice(n, 3);
  std::mt19937_64 rng(1);
  for (double m : {1.5, 3.015})
    for (int threads : {1, omp_get_max_threads()}) {
      SearchOptions options;
      options.horizon = m * 10.0 / n;
      options.backend = threads == 1 ? Backend::serial : Backend::openmp;
      options.threads = threads;
      const double skin = skin_fraction * options.horizon;
      Stopwatch clock;
      const VerletList verlet(points.view(), options, skin);
      const double build = clock.lap();
      PointSet now = points;
      std::uniform_real_distribution<double> step(-skin / 5 / 3, skin / 5 / 3);  // |d| < skin / 5
      for (double& x : now.xyz) x += step(rng);
      NeighborList fresh, refreshed;
      const double search_s = median_seconds(reps, [&] { fresh = search(now.view(), options); });
      const double refresh_s = median_seconds(reps, [&] { refreshed = verlet.refresh(now.view(), threads); });
      bool rebuild = false;
      const double check_s = median_seconds(reps, [&] { rebuild = verlet.needs_rebuild(now.view(), threads); });
      if (rebuild || !(fresh == refreshed)) {
        std::fprintf(stderr, "refresh differs from a fresh search (or a rebuild was asked for)\n");
        return 1;
      }
      std::printf("%g,%d,%lld,%lld,%.4f,%.4f,%.4f,%.4f,%.2f\n", m, threads, static_cast<long long>(fresh.total()),
                  static_cast<long long>(verlet.candidates().total()), build, search_s, refresh_s, check_s,
                  search_s / refresh_s);
    }
  return 0;
}
