// What calling through the C API costs: horizon_search (horizon.h, linked from libhorizon.so)
// against horizon::search on the same points in the same process, alternating, each list freed
// before the next call as a solver searching every step does. Prints CSV; c_over_cpp is the
// ratio of the medians.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <tuple>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/horizon.h"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"
#include "median_seconds.hpp"

int main(int argc, char** argv) {
  CLI::App app{"horizon through its C API against the C++ call"};
  int reps = 7;
  std::size_t points = 1000000;
  app.add_option("--reps", reps, "calls of each, alternating (median)");
  app.add_option("--points", points, "points of the random cloud (the lattice has 100^3)");
  CLI11_PARSE(app, argc, argv);

  std::printf("problem,points,m,backend,threads,entries,cpp_s,c_s,c_over_cpp\n");
  const horizon::PointSet lattice = horizon::lattice(100);
  const horizon::PointSet cloud = horizon::random_cloud(points, 3, 7);
  for (const auto& [name, set, spacing] : {std::tuple{"lattice", &lattice, 0.1}, std::tuple{"random", &cloud, 10.0 / std::cbrt(static_cast<double>(points))}}) {
    for (double m : {1.5, 3.015}) {
      for (horizon_backend backend : {HORIZON_BACKEND_SERIAL, HORIZON_BACKEND_OPENMP}) {
        horizon::SearchOptions cpp;
        cpp.horizon = m * spacing;
        cpp.backend = static_cast<horizon::Backend>(backend);
        horizon_options c;
        horizon_options_default(&c);
        c.horizon = cpp.horizon;
        c.backend = backend;
        std::vector<double> cpp_s, c_s;
        std::int64_t entries = 0;
        horizon::SearchStats stats;
        const auto call_cpp = [&] {
          horizon::Stopwatch clock;
          const horizon::NeighborList list = horizon::search(set->view(), cpp, &stats);
          cpp_s.push_back(clock.lap());
          entries = list.total();
        };
        const auto call_c = [&] {
          horizon::Stopwatch clock;
          horizon_list* list = nullptr;
          if (horizon_search(set->xyz.data(), set->size(), 3, &c, &list) != HORIZON_OK) {
            std::fprintf(stderr, "%s\n", horizon_last_error());
            std::exit(2);
          }
          horizon_list_free(list);
          c_s.push_back(clock.lap());
        };
        for (int r = 0; r < reps; ++r) {  // alternating which goes first, so neither gains from order
          if (r % 2) {
            call_c();
            call_cpp();
          } else {
            call_cpp();
            call_c();
          }
        }
        std::printf("%s,%zu,%g,%s,%d,%lld,%.4f,%.4f,%.3f\n", name, set->size(), m, horizon::backend_name(cpp.backend),
                    stats.threads, static_cast<long long>(entries), median(cpp_s), median(c_s), median(c_s) / median(cpp_s));
      }
    }
  }
  return 0;
}
