// Periodic boxes and queries against a separate reference set, on every backend, against the
// brute-force oracle (which tries every periodic image of every pair).
#include <gtest/gtest.h>

#include <tuple>

#include "datasets.hpp"
#include "horizon/error.hpp"
#include "horizon/oracle.hpp"
#include "horizon/search.hpp"
#include "require_backend.hpp"

namespace horizon::testing {
namespace {

using Case = std::tuple<Backend, Metric, int /*dims*/, bool /*half*/>;

/// Point sets inside [0, side)^dims with a box that fits them, chosen to stress the wrap.
struct BoxedDataset {
  std::string name;
  PointSet points;
  double horizon;
  std::array<double, 3> box;
};

std::vector<BoxedDataset> boxed(int dims) {
  std::vector<BoxedDataset> all;
  const double z = dims == 3 ? 10 : 0;
  all.push_back({"random", random_cloud(900, dims, 3), dims == 3 ? 1.6 : 0.6, {10, 10, z}});
  all.push_back({"random_mixed_axes", random_cloud(900, dims, 4), dims == 3 ? 1.6 : 0.6, {10, 0, z}});
  const int n = dims == 3 ? 9 : 30;
  all.push_back({"lattice_m3.015", lattice(n, dims), 3.015 * 10.0 / n, {10, 10, z}});
  // Integer coordinates 0..8 in a box of 9 with horizon 3: ties exactly on the horizon across
  // the periodic faces, points on the faces themselves.
  const double side = dims == 3 ? 9 : 25;
  all.push_back({"integer_ties", integer_cloud(500, dims, static_cast<int>(side), 11), 3.0,
                 {side, side, dims == 3 ? side : 0}});
  // Points hugging both faces of each axis, and a horizon just under half the box.
  PointSet faces{dims, {}};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> near(0.0, 0.05);
  for (int i = 0; i < 400; ++i)
    for (int a = 0; a < dims; ++a) faces.xyz.push_back(i % 2 ? near(rng) : std::nextafter(4.0, 0.0) - near(rng));
  all.push_back({"faces", faces, 1.999, {4, 4, dims == 3 ? 4.0 : 0.0}});
  // A few points near the corners of a huge box: the grid is sparse (cells looked up by
  // coordinates, not by a table), and every pair is across a face.
  PointSet corners{dims, {}};
  const double huge = 1e8;
  std::uniform_real_distribution<double> offset(0.0, 2000.0);
  for (int i = 0; i < 300; ++i)
    for (int a = 0; a < dims; ++a) corners.xyz.push_back((i >> a) % 2 ? offset(rng) : huge - offset(rng));
  all.push_back({"sparse_corners", corners, 1500.0, {huge, huge, dims == 3 ? huge : 0.0}});
  return all;
}

class PeriodicTest : public ::testing::TestWithParam<Case> {};

TEST_P(PeriodicTest, SameListAsBruteForce) {
  const auto [backend, metric, dims, half] = GetParam();
  require(backend);
  if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
  for (const BoxedDataset& data : boxed(dims)) {
    for (bool sorted : {true, false}) {
      SearchOptions options;
      options.horizon = data.horizon;
      options.metric = metric;
      options.half = half;
      options.backend = backend;
      options.box = data.box;
      options.sort_rows = sorted;
      const NeighborList list = search(data.points.view(), options);
      const NeighborList expected = brute_force(data.points.view(), options);
      ASSERT_EQ(list.offsets(), expected.offsets()) << data.name;
      if (sorted) {
        EXPECT_EQ(list.indices(), expected.indices()) << data.name;
        continue;
      }
      for (std::size_t i = 0; i < list.size(); ++i) {
        std::vector<point_id> row(list.row(i).begin(), list.row(i).end());
        std::sort(row.begin(), row.end());
        ASSERT_TRUE(std::equal(row.begin(), row.end(), expected.row(i).begin(), expected.row(i).end()))
            << data.name << " row " << i;
      }
    }
  }
}

class QueryReferenceTest : public ::testing::TestWithParam<Case> {};

TEST_P(QueryReferenceTest, SameListAsBruteForce) {
  const auto [backend, metric, dims, periodic] = GetParam();
  require(backend);
  if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
  PointSet refs = clustered_cloud(1000, 5, 0.8, dims, 2);
  if (periodic)  // the clusters spill out of [0, 10): fold them in
    for (double& x : refs.xyz) {
      x = std::fmod(std::fmod(x, 10.0) + 10.0, 10.0);
      x = x >= 10.0 ? 0.0 : x;
    }
  PointSet queries = random_cloud(300, dims, 8);
  // Some queries sit exactly on references: nothing is excluded as "self".
  queries.xyz.insert(queries.xyz.end(), refs.xyz.begin(), refs.xyz.begin() + 20 * dims);
  SearchOptions options;
  options.horizon = dims == 3 ? 0.9 : 0.3;
  options.metric = metric;
  options.backend = backend;
  if (periodic) options.box = {10, 10, dims == 3 ? 10.0 : 0.0};
  const NeighborList list = search(queries.view(), refs.view(), options);
  const NeighborList expected = brute_force(queries.view(), refs.view(), options);
  ASSERT_EQ(list.size(), queries.size());
  EXPECT_EQ(list.offsets(), expected.offsets());
  EXPECT_EQ(list.indices(), expected.indices());
  for (std::size_t q = 300; q < queries.size(); ++q) EXPECT_FALSE(list.row(q).empty()) << "query " << q;
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  const auto [backend, metric, dims, flag] = info.param;
  return std::string(backend_name(backend)) + "_" + metric_name(metric) + "_" + std::to_string(dims) + "d" +
         (flag ? "_on" : "_off");
}

const auto all_cases = ::testing::Combine(::testing::Values(Backend::serial, Backend::openmp, Backend::cuda),
                                          ::testing::Values(Metric::euclidean, Metric::manhattan, Metric::chebyshev),
                                          ::testing::Values(2, 3), ::testing::Bool());
// The flag is the half list for PeriodicTest and the periodic box for QueryReferenceTest.
INSTANTIATE_TEST_SUITE_P(AllBackends, PeriodicTest, all_cases, case_name);
INSTANTIATE_TEST_SUITE_P(AllBackends, QueryReferenceTest, all_cases, case_name);

void expect_error(PointView points, const SearchOptions& options, const std::string& message) {
  try {
    search(points, options);
    ADD_FAILURE() << "no error; expected: " << message;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(PeriodicBox, BadInputIsRefusedClearly) {
  const PointSet points{3, {1, 1, 1, 2, 11, 3, 4, 4, 4}};
  SearchOptions options;
  options.horizon = 1;
  options.box = {10, 10, 10};
  expect_error(points.view(), options, "point 1 has y = 11.000000, outside the periodic box [0, 10.000000)");
  const PointSet inside{3, {1, 1, 1, 9.5, 9.5, 9.5}};
  options.horizon = 5;
  expect_error(inside.view(), options, "must be below half the period");
  options.horizon = 1;
  options.box = {10, -1, 0};
  expect_error(inside.view(), options, "period on axis y must be finite and >= 0");
  const PointSet flat{2, {1, 1, 2, 2}};
  options.box = {10, 10, 10};
  expect_error(flat.view(), options, "a period on axis z but the points are 2-D");
  SearchOptions half;
  half.horizon = 1;
  half.half = true;
  EXPECT_THROW(search(inside.view(), flat.view(), half), Error);  // dims differ
  EXPECT_THROW(search(inside.view(), inside.view(), half), Error);  // half with references
}

TEST(PeriodicBox, EveryNeighbourAcrossTheFaceOnce) {
  // Two points 0.2 apart through the x face of a box of 10: one entry each, not two.
  const PointSet points{3, {0.1, 5, 5, 9.9, 5, 5}};
  SearchOptions options;
  options.horizon = 0.5;
  options.box = {10, 0, 0};
  const NeighborList list = search(points.view(), options);
  ASSERT_EQ(list.total(), 2);
  EXPECT_EQ(list.row(0)[0], 1);
  options.box = {0, 0, 0};
  EXPECT_EQ(search(points.view(), options).total(), 0);
}

}  // namespace
}  // namespace horizon::testing
