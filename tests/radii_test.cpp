// Per-point radii: every rule x backend x metric x dimension x list kind (x periodic box) against
// the brute-force oracle, which tests each pair with the radius the rule gives it.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

#include "datasets.hpp"
#include "horizon/error.hpp"
#include "horizon/oracle.hpp"
#include "horizon/radii.hpp"
#include "require_backend.hpp"

namespace horizon::testing {
namespace {

/// Radii from `low` to `high` times the dataset's horizon, log-uniform: several radius classes.
std::vector<double> radii_for(const Dataset& data, double low, double high, std::uint64_t seed) {
  if (low == 0) return std::vector<double>(data.points.size());
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> exponent(std::log(low), std::log(high));
  std::vector<double> radii(data.points.size());
  for (double& r : radii) r = data.horizon * std::exp(exponent(rng));
  return radii;
}

/// The brute-force list, computed once for every backend (the O(N^2) oracle dominates the time).
const NeighborList& oracle(const Dataset& data, const std::vector<double>& radii, RadiusRule rule,
                           const SearchOptions& options, double setting) {
  static std::map<std::tuple<std::string, int, RadiusRule, Metric, bool, double>, NeighborList> cache;
  const auto key = std::make_tuple(data.name, data.points.dims, rule, options.metric, options.half, setting);
  auto it = cache.find(key);
  if (it == cache.end())
    it = cache.emplace(key, brute_force_with_radii(data.points.view(), radii, rule, options)).first;
  return it->second;
}

using Case = std::tuple<Backend, RadiusRule, Metric, int /*dims*/, bool /*half*/>;

class RadiiTest : public ::testing::TestWithParam<Case> {};

TEST_P(RadiiTest, SameListAsBruteForce) {
  const auto [backend, rule, metric, dims, half] = GetParam();
  require(backend);
  if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
  for (const Dataset& data : datasets(dims)) {
    // (huge_extent: radii spanning 10x a 10^-3 horizon over 10^12; dense: the plain oracle's)
    if (data.name == "huge_extent" || data.name == "dense") continue;
    SearchOptions options = options_for(data, metric, 1, half, backend);
    // Radii over 10x (four classes); all equal (one class: the same list as one horizon); and
    // two values, 2/3 and 1 of the horizon: on integer_ties, pairs exactly at the smaller radius
    // come from the search at the larger one and must be dropped.
    for (const auto& [low, high] : {std::pair{0.3, 3.0}, std::pair{1.0, 1.0}, std::pair{0.0, 0.0}}) {
      if (low == 0 && data.name != "integer_ties") continue;
      std::vector<double> radii = radii_for(data, low, high, 5);
      if (low == 0)
        for (std::size_t i = 0; i < radii.size(); ++i) radii[i] = data.horizon * (i % 3 ? 1.0 : 2.0 / 3.0);
      const NeighborList list = search_with_radii(data.points.view(), radii, rule, options);
      const NeighborList& expected = oracle(data, radii, rule, options, low);
      const std::string where = data.name + " radii " + std::to_string(low) + "-" + std::to_string(high);
      ASSERT_EQ(list.offsets(), expected.offsets()) << where;
      EXPECT_EQ(list.indices(), expected.indices()) << where;
      EXPECT_EQ(list.is_half(), half);
      if (low == 1.0 && high == 1.0 && data.points.size() > 0) {  // one radius: the plain search's list
        SearchOptions plain = options;
        plain.horizon = radii[0];
        EXPECT_EQ(list.indices(), search(data.points.view(), plain).indices()) << where;
      }
    }
  }
}

TEST_P(RadiiTest, PeriodicBoxMatchesBruteForce) {
  const auto [backend, rule, metric, dims, half] = GetParam();
  require(backend);
  if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
  // 600 points in [0, 10)^dims, periodic in x and y (open in z): radii 0.4 ... 2.4.
  PointSet points = random_cloud(600, dims, 23);
  Dataset data{"box", points, 0.8};
  SearchOptions options = options_for(data, metric, 1, half, backend);
  options.box = {10, 10, 0};
  const std::vector<double> radii = radii_for(data, 0.5, 3.0, 9);
  const NeighborList list = search_with_radii(points.view(), radii, rule, options);
  const NeighborList expected = brute_force_with_radii(points.view(), radii, rule, options);
  ASSERT_EQ(list.offsets(), expected.offsets());
  EXPECT_EQ(list.indices(), expected.indices());
}

// Queries have one radius each and full rows (the gather rule): no rule or list kind to vary.
using QueryCase = std::tuple<Backend, Metric, int /*dims*/>;

class RadiiQueryTest : public ::testing::TestWithParam<QueryCase> {};

TEST_P(RadiiQueryTest, QueriesWithTheirOwnRadiiMatchBruteForce) {
  const auto [backend, metric, dims] = GetParam();
  require(backend);
  if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
  // 400 queries (a quarter of them on reference points: nothing is excluded as self) against
  // each dataset, radii over 10x; and in a periodic box.
  for (const Dataset& data : datasets(dims)) {
    if (data.name == "huge_extent" || data.name == "dense" || data.points.size() == 0) continue;
    PointSet queries = random_cloud(300, dims, 41);
    queries.xyz.insert(queries.xyz.end(), data.points.xyz.begin(),
                       data.points.xyz.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(100, data.points.size()) * dims));
    const Dataset query_data{data.name, queries, data.horizon};
    const std::vector<double> radii = radii_for(query_data, 0.3, 3.0, 6);
    const SearchOptions options = options_for(data, metric, 1, false, backend);
    const NeighborList list = search_with_radii(queries.view(), radii, data.points.view(), options);
    const NeighborList expected = brute_force_with_radii(queries.view(), radii, data.points.view(), options);
    ASSERT_EQ(list.offsets(), expected.offsets()) << data.name;
    EXPECT_EQ(list.indices(), expected.indices()) << data.name;
  }
  const PointSet references = random_cloud(600, dims, 23), queries = random_cloud(200, dims, 29);
  SearchOptions options = options_for(Dataset{"box", references, 0.8}, metric, 1, false, backend);
  options.box = {10, 10, 0};
  const std::vector<double> radii = radii_for(Dataset{"box", queries, 0.8}, 0.5, 3.0, 8);
  EXPECT_EQ(search_with_radii(queries.view(), radii, references.view(), options),
            brute_force_with_radii(queries.view(), radii, references.view(), options));
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  const auto [backend, rule, metric, dims, half] = info.param;
  return std::string(backend_name(backend)) + "_" + radius_rule_name(rule) + "_" + metric_name(metric) + "_" +
         std::to_string(dims) + "d" + (half ? "_half" : "_full");
}

/// Every combination the API accepts: half lists only with the symmetric rules (max, min); the
/// others are refused, which RadiiErrors tests.
std::vector<Case> accepted_cases() {
  std::vector<Case> cases;
  for (Backend backend : {Backend::serial, Backend::openmp, Backend::cuda})
    for (RadiusRule rule : {RadiusRule::gather, RadiusRule::scatter, RadiusRule::max, RadiusRule::min})
      for (Metric metric : {Metric::euclidean, Metric::manhattan, Metric::chebyshev})
        for (int dims : {2, 3})
          for (bool half : {false, true})
            if (!half || rule == RadiusRule::max || rule == RadiusRule::min)
              cases.emplace_back(backend, rule, metric, dims, half);
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllBackends, RadiiTest, ::testing::ValuesIn(accepted_cases()), case_name);

std::string query_case_name(const ::testing::TestParamInfo<QueryCase>& info) {
  const auto [backend, metric, dims] = info.param;
  return std::string(backend_name(backend)) + "_" + metric_name(metric) + "_" + std::to_string(dims) + "d";
}

INSTANTIATE_TEST_SUITE_P(AllBackends, RadiiQueryTest,
                         ::testing::Combine(::testing::Values(Backend::serial, Backend::openmp, Backend::cuda),
                                            ::testing::Values(Metric::euclidean, Metric::manhattan, Metric::chebyshev),
                                            ::testing::Values(2, 3)),
                         query_case_name);

TEST(RadiiThreads, EveryRuleGivesTheSameListOnAnyThreadCount) {
  // The transpose splits the rows into one part per thread: parts of uneven sizes, some empty.
  const PointSet points = random_cloud(3000, 3, 11);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> radius(0.5, 2.0);  // radius classes 1 and 2
  std::vector<double> radii(points.size());
  for (double& r : radii) r = radius(rng);
  for (const RadiusRule rule : {RadiusRule::scatter, RadiusRule::max, RadiusRule::min})
    for (const bool half : {false, true}) {
      if (half && rule == RadiusRule::scatter) continue;
      SearchOptions options;
      options.backend = Backend::openmp;
      options.half = half;
      options.threads = 1;
      const NeighborList expected = brute_force_with_radii(points.view(), radii, rule, options);
      for (const int threads : {1, 3, 7, 16}) {
        options.threads = threads;
        EXPECT_EQ(search_with_radii(points.view(), radii, rule, options), expected)
            << radius_rule_name(rule) << (half ? " half, " : " full, ") << threads << " threads";
      }
    }
}

TEST(RadiiErrors, NameThePointOrTheRule) {
  const PointSet points = lattice(4);
  SearchOptions options;
  std::vector<double> radii(points.size(), 1.0);
  auto message = [&](RadiusRule rule) {
    try {
      search_with_radii(points.view(), radii, rule, options);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  radii[7] = -0.5;
  EXPECT_EQ(message(RadiusRule::gather), "radii: point 7 has radius -0.500000 (each must be finite and > 0)");
  radii[7] = std::nan("");
  EXPECT_NE(message(RadiusRule::max).find("point 7"), std::string::npos);
  radii[7] = 1.0;
  radii.pop_back();
  EXPECT_EQ(message(RadiusRule::gather), "radii: 63 radii for 64 points");
  radii.push_back(1.0);
  const PointSet queries = lattice(2);  // 8 queries
  auto query_message = [&](const std::vector<double>& r, const SearchOptions& o) {
    try {
      search_with_radii(queries.view(), r, points.view(), o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(query_message(std::vector<double>(7, 1.0), options), "radii: 7 radii for 8 queries");
  EXPECT_EQ(query_message({1, 1, 1, 0, 1, 1, 1, 1}, options), "radii: query 3 has radius 0.000000 (each must be finite and > 0)");
  options.half = true;
  EXPECT_NE(query_message(std::vector<double>(8, 1.0), options).find("half lists are about one point set"), std::string::npos);
  EXPECT_NE(message(RadiusRule::scatter).find("half list needs a symmetric rule"), std::string::npos);
  EXPECT_EQ(message(RadiusRule::min), "no error");
  options.half = false;
  options.box = {12, 0, 0};
  radii[3] = 6.0;
  EXPECT_NE(message(RadiusRule::gather).find("largest radius 6.000000 must be below half the period"),
            std::string::npos);
  EXPECT_THROW(parse_radius_rule("mean"), Error);
  EXPECT_EQ(parse_radius_rule("scatter"), RadiusRule::scatter);
}

}  // namespace
}  // namespace horizon::testing
