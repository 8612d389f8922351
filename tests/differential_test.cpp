// Differential random testing: small problems drawn from a fixed seed, each solved by every
// backend built here and by the brute-force oracle, which must agree exactly. The draws aim at
// what nobody writes down: duplicates, collinear and coplanar points, coordinates on exact
// multiples of the horizon and of the cell side, offsets up to 10^12, float32 input, horizons
// from tiny to larger than the cloud, every metric, k = 1-3, full and half lists, queries.
// Every problem is also built in batches of rows (search_in_batches). HORIZON_DIFFERENTIAL_PROBLEMS
// sets the count (default 1000), HORIZON_DIFFERENTIAL_SEED the seed (to run shards in parallel).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "assemble_batches.hpp"
#include "horizon/oracle.hpp"
#include "horizon/search.hpp"

namespace horizon::testing {
namespace {

struct Problem {
  int dims = 3;
  std::vector<double> xyz;
  bool single = false;  // search the float32 rounding of the coordinates
  SearchOptions options;
  std::string describe() const {
    std::ostringstream out;
    out << xyz.size() / dims << " points, " << dims << "-D, horizon " << options.horizon << ", "
        << metric_name(options.metric) << ", k " << options.cells_per_horizon << (options.half ? ", half" : "")
        << (single ? ", float32" : "") << (options.queries ? ", queries " + std::to_string(options.queries) : "");
    return out.str();
  }
};

Problem draw(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<std::uint64_t>(n)); };
  Problem p;
  p.dims = pick(2) ? 3 : 2;
  const int count = pick(8) == 0 ? pick(4) : pick(3000);
  const double side = std::pow(10.0, uniform(-3, 3));
  const double offset = pick(4) == 0 ? std::pow(10.0, uniform(0, 12)) * (pick(2) ? 1 : -1) : 0.0;
  p.options.horizon = side * std::pow(10.0, uniform(-3, 0.5));  // tiny to larger than the cloud
  p.options.metric = static_cast<Metric>(pick(3));
  p.options.cells_per_horizon = 1 + pick(3);
  p.options.half = pick(2);
  p.single = pick(5) == 0;
  const int shape = pick(6);
  for (int i = 0; i < count; ++i) {
    double x[3];
    for (int a = 0; a < p.dims; ++a) x[a] = uniform(0, side);
    if (shape == 1) {  // on exact multiples of the horizon or of the cell side
      const double unit = p.options.horizon / (pick(2) ? 1 : p.options.cells_per_horizon);
      for (int a = 0; a < p.dims; ++a) x[a] = unit * pick(12);
    } else if (shape == 2) {  // collinear
      const double t = uniform(0, side);
      for (int a = 0; a < p.dims; ++a) x[a] = t * (a + 1) * 0.25;
    } else if (shape == 3) {  // coplanar (z = 0, or y = x in 2-D)
      x[p.dims - 1] = p.dims == 3 ? 0.0 : x[0];
    } else if (shape == 4 && i > 0 && pick(3)) {  // duplicates of earlier points
      const int j = pick(i);
      for (int a = 0; a < p.dims; ++a) x[a] = p.xyz[static_cast<std::size_t>(j * p.dims + a)] - offset;
    }
    for (int a = 0; a < p.dims; ++a) p.xyz.push_back(x[a] + offset);
  }
  if (p.single)
    for (double& v : p.xyz) v = static_cast<double>(static_cast<float>(v));
  if (count > 0 && pick(6) == 0) p.options.queries = static_cast<std::size_t>(1 + pick(count));
  return p;
}

int problem_count() {
  const char* value = std::getenv("HORIZON_DIFFERENTIAL_PROBLEMS");
  return value ? std::atoi(value) : 1000;
}

std::uint64_t seed() {
  const char* value = std::getenv("HORIZON_DIFFERENTIAL_SEED");
  return value ? std::strtoull(value, nullptr, 10) : 20261123;
}

TEST(Differential, EveryBackendAgreesWithTheOracleOnRandomProblems) {
  std::vector<Backend> backends{Backend::serial, Backend::openmp};
  if (backend_available(Backend::cuda)) backends.push_back(Backend::cuda);
  std::mt19937_64 rng(seed());
  int compared = 0;
  for (int n = 0; n < problem_count(); ++n) {
    const Problem p = draw(rng);
    const std::size_t count = p.xyz.size() / static_cast<std::size_t>(p.dims);
    std::vector<float> single(p.xyz.begin(), p.xyz.end());
    const PointView view = p.single ? PointView(single.data(), count, p.dims) : PointView(p.xyz.data(), count, p.dims);
    const NeighborList expected = brute_force(PointView(p.xyz.data(), count, p.dims), p.options);
    for (Backend backend : backends) {
      SearchOptions options = p.options;
      options.backend = backend;
      ASSERT_EQ(search(view, options), expected) << "problem " << n << " of seed " << seed() << " (" << p.describe() << "), backend "
                                                 << backend_name(backend);
      ++compared;
    }
    const std::int64_t batch_entries = 1 + expected.total() / (2 + n % 7);  // 2 to 8 batches
    ASSERT_EQ(assemble_batches(view, p.options, batch_entries), expected)
        << "problem " << n << " (" << p.describe() << "), in batches of " << batch_entries;
  }
  EXPECT_EQ(compared, static_cast<int>(backends.size()) * problem_count());
}

}  // namespace
}  // namespace horizon::testing
