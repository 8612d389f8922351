// horizon_radii_bench: per-point radii against one radius giving the same number of entries.
// A clustered cloud (DESIGN.md's) with radii log-uniform over a span (10x by default) around the
// horizon of m = 1.5; for each rule the single radius with the same entry count (+-0.5 %) is
// found by bisection and both searches are timed on the same points, one core and all; CSV
// with the ratio (issue 12's target: radii <= 2x the single radius).
#include <CLI/CLI.hpp>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/radii.hpp"
#include "horizon/stopwatch.hpp"
#include "median_seconds.hpp"

using namespace horizon;

int main(int argc, char** argv) {
  CLI::App app{"horizon_radii_bench: per-point radii against one radius with as many entries, as CSV"};
  std::size_t count = 1000000;
  int reps = 3;
  double span = 10, horizon = 0.15;
  app.add_option("--points", count, "points in the clustered cloud");
  app.add_option("--span", span, "largest / smallest radius");
  app.add_option("--horizon", horizon, "geometric middle of the radii");
  app.add_option("--reps", reps, "repetitions (the median is reported)");
  std::vector<std::string> rule_names{"gather", "scatter", "max", "min"};
  app.add_option("--rules", rule_names, "rules to run")->delimiter(',');
  CLI11_PARSE(app, argc, argv);

  const PointSet points = clustered_cloud(count, 64, 1.0, 3, 2);  // horizon_bench's clustered cloud
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> exponent(-0.5 * std::log(span), 0.5 * std::log(span));
  std::vector<double> radii(points.size());
  for (double& r : radii) r = horizon * std::exp(exponent(rng));

  std::printf("# %d hardware threads; clustered cloud of %zu points (64 clusters, sigma 1), radii log-uniform "
              "over %gx around %g\n", omp_get_max_threads(), count, span, horizon);
  std::printf("rule,backend,threads,entries,single_radius,single_entries,radii_s,single_s,radii_over_single\n");
  for (const std::string& name : rule_names) {
    const RadiusRule rule = parse_radius_rule(name);
    SearchOptions options;
    options.backend = Backend::openmp;
    const std::int64_t entries = search_with_radii(points.view(), radii, rule, options).total();
    // The single radius with as many entries: bisection on the openmp search.
    double low = horizon / std::sqrt(span), high = horizon * std::sqrt(span), single = horizon;
    std::int64_t single_entries = 0;
    for (int step = 0; step < 40; ++step) {
      SearchOptions one = options;
      one.horizon = single = 0.5 * (low + high);
      single_entries = search(points.view(), one).total();
      if (std::abs(static_cast<double>(single_entries - entries)) <= 0.005 * static_cast<double>(entries)) break;
      (single_entries < entries ? low : high) = single;
    }
    for (const Backend backend : {Backend::serial, Backend::openmp}) {
      options.backend = backend;
      SearchOptions one = options;
      one.horizon = single;
      const double radii_s = median_seconds(reps, [&] { search_with_radii(points.view(), radii, rule, options); });
      const double single_s = median_seconds(reps, [&] { search(points.view(), one); });
      std::printf("%s,%s,%d,%lld,%.6g,%lld,%.4f,%.4f,%.2f\n", radius_rule_name(rule), backend_name(backend),
                  backend == Backend::serial ? 1 : omp_get_max_threads(), static_cast<long long>(entries), single,
                  static_cast<long long>(single_entries), radii_s, single_s, radii_s / single_s);
      std::fflush(stdout);
    }
  }
}
