// Every backend x metric x dimension x cell size x list kind against the brute-force oracle.
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "datasets.hpp"
#include "horizon/oracle.hpp"
#include "horizon/search.hpp"
#include "require_backend.hpp"

namespace horizon::testing {
namespace {

using Case = std::tuple<Backend, Metric, int /*dims*/, int /*k*/, bool /*half*/>;

class OracleTest : public ::testing::TestWithParam<Case> {};

const NeighborList& oracle(const Dataset& data, Metric metric, bool half) {
  static std::map<std::tuple<std::string, int, Metric, bool>, NeighborList> cache;
  const auto key = std::make_tuple(data.name, data.points.dims, metric, half);
  auto it = cache.find(key);
  if (it == cache.end()) {
    it = cache.emplace(key, brute_force(data.points.view(), options_for(data, metric, 1, half))).first;
  }
  return it->second;
}

TEST_P(OracleTest, SameListAsBruteForce) {
  const auto [backend, metric, dims, k, half] = GetParam();
  require(backend);
  if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
  for (const Dataset& data : datasets(dims)) {
    const NeighborList list = search(data.points.view(), options_for(data, metric, k, half, backend));
    const NeighborList& expected = oracle(data, metric, half);
    ASSERT_EQ(list.size(), expected.size()) << data.name;
    EXPECT_EQ(list.offsets(), expected.offsets()) << data.name;
    EXPECT_EQ(list.indices(), expected.indices()) << data.name;
    EXPECT_EQ(list.is_half(), half);
  }
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  const auto [backend, metric, dims, k, half] = info.param;
  return std::string(backend_name(backend)) + "_" + metric_name(metric) + "_" + std::to_string(dims) +
         "d_k" + std::to_string(k) + (half ? "_half" : "_full");
}

INSTANTIATE_TEST_SUITE_P(
    AllBackends, OracleTest,
    ::testing::Combine(::testing::Values(Backend::serial, Backend::openmp, Backend::cuda),
                       ::testing::Values(Metric::euclidean, Metric::manhattan, Metric::chebyshev),
                       ::testing::Values(2, 3), ::testing::Values(1, 2, 3), ::testing::Bool()),
    case_name);

}  // namespace
}  // namespace horizon::testing
