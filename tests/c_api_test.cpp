// The C API (horizon/horizon.h) against the brute-force oracle on the datasets every backend is
// tested on, and every error path: a status and a message naming the cause, never an exception.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#if defined(HORIZON_WITH_CUDA)
#include <cuda_runtime.h>
#endif

#include "datasets.hpp"
#include "horizon/block_filter.hpp"
#include "horizon/bond_filter.hpp"
#include "horizon/horizon.h"
#include "horizon/oracle.hpp"
#include "horizon/radii.hpp"
#include "horizon/verlet_list.hpp"

namespace horizon::testing {
namespace {

horizon_options c_options(const Dataset& data, horizon_metric metric, bool half, horizon_backend backend) {
  horizon_options options;
  horizon_options_default(&options);
  options.horizon = data.horizon;
  options.metric = metric;
  options.half = half;
  options.backend = backend;
  return options;
}

Metric cpp_metric(horizon_metric metric) {
  return metric == HORIZON_METRIC_L2 ? Metric::euclidean : metric == HORIZON_METRIC_L1 ? Metric::manhattan : Metric::chebyshev;
}

/// The C list as a NeighborList, to compare with the oracle's (and freed).
NeighborList take(horizon_list* list) {
  EXPECT_NE(list, nullptr);
  if (list == nullptr) return {};
  const std::size_t n = horizon_list_size(list);
  Buffer<std::int64_t> offsets(horizon_list_offsets(list), horizon_list_offsets(list) + n + 1);
  Buffer<point_id> indices(horizon_list_indices(list), horizon_list_indices(list) + horizon_list_total(list));
  const bool half = horizon_list_is_half(list);
  horizon_list_free(list);
  return NeighborList(std::move(offsets), std::move(indices), half);
}

using Case = std::tuple<horizon_backend, horizon_metric, int /*dims*/, bool /*half*/>;

class CApiTest : public ::testing::TestWithParam<Case> {
protected:
  void SetUp() override {
    if (!horizon_backend_available(std::get<0>(GetParam()))) {
      const char* required = std::getenv("HORIZON_REQUIRE_GPU");
      if (required && std::string(required) == "1") FAIL() << "HORIZON_REQUIRE_GPU=1 but the backend is not usable";
      GTEST_SKIP() << "backend not available here (no GPU)";
    }
  }
};

TEST_P(CApiTest, SearchMatchesBruteForce) {
  const auto [backend, metric, dims, half] = GetParam();
  for (const Dataset& data : datasets(dims)) {
    const horizon_options options = c_options(data, metric, half, backend);
    horizon_list* list = nullptr;
    ASSERT_EQ(horizon_search(data.points.xyz.data(), data.points.size(), dims, &options, &list), HORIZON_OK)
        << data.name << ": " << horizon_last_error();
    SearchOptions expected_options = options_for(data, cpp_metric(metric), 1, half);
    EXPECT_EQ(take(list), brute_force(data.points.view(), expected_options)) << data.name;
  }
}

TEST_P(CApiTest, RadiiQueriesAndABoxMatchBruteForce) {
  const auto [backend, metric, dims, half] = GetParam();
  const PointSet points = random_cloud(700, dims, 23), queries = random_cloud(150, dims, 29);
  const Dataset data{"cloud", points, 0.8};
  std::vector<double> radii(points.size());
  for (std::size_t i = 0; i < radii.size(); ++i) radii[i] = 0.3 + 1.2 * static_cast<double>(i % 7) / 6;
  horizon_options options = c_options(data, metric, half, backend);
  SearchOptions expected = options_for(data, cpp_metric(metric), 1, half);
  horizon_list* list = nullptr;

  const horizon_radius_rule rule = half ? HORIZON_RADIUS_MAX : HORIZON_RADIUS_GATHER;
  ASSERT_EQ(horizon_search_radii(points.xyz.data(), points.size(), dims, radii.data(), rule, &options, &list), HORIZON_OK)
      << horizon_last_error();
  EXPECT_EQ(take(list), brute_force_with_radii(points.view(), radii, half ? RadiusRule::max : RadiusRule::gather, expected));

  options.box[0] = options.box[1] = 10;  // periodic in x and y
  expected.box = {10, 10, 0};
  ASSERT_EQ(horizon_search(points.xyz.data(), points.size(), dims, &options, &list), HORIZON_OK) << horizon_last_error();
  EXPECT_EQ(take(list), brute_force(points.view(), expected));
  if (half) return;  // query lists are full

  ASSERT_EQ(horizon_search_queries(queries.xyz.data(), queries.size(), points.xyz.data(), points.size(), dims, nullptr,
                                   &options, &list), HORIZON_OK) << horizon_last_error();
  EXPECT_EQ(take(list), brute_force(queries.view(), points.view(), expected));
  std::vector<double> query_radii(queries.size(), 0.6);
  ASSERT_EQ(horizon_search_queries(queries.xyz.data(), queries.size(), points.xyz.data(), points.size(), dims,
                                   query_radii.data(), &options, &list), HORIZON_OK) << horizon_last_error();
  EXPECT_EQ(take(list), brute_force_with_radii(queries.view(), query_radii, points.view(), expected));
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  const auto [backend, metric, dims, half] = info.param;
  const char* backends[] = {"auto", "serial", "openmp", "cuda"};
  const char* metrics[] = {"l2", "l1", "linf"};
  return std::string(backends[backend]) + "_" + metrics[metric] + "_" + std::to_string(dims) + "d" + (half ? "_half" : "_full");
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, CApiTest,
                         ::testing::Combine(::testing::Values(HORIZON_BACKEND_SERIAL, HORIZON_BACKEND_OPENMP, HORIZON_BACKEND_CUDA),
                                            ::testing::Values(HORIZON_METRIC_L2, HORIZON_METRIC_L1, HORIZON_METRIC_LINF),
                                            ::testing::Values(2, 3), ::testing::Bool()),
                         case_name);

TEST(CApi, FiltersVerletListsAndOneBasedIds) {
  const PointSet points = lattice(12);  // spacing 10/12
  horizon_options options;
  horizon_options_default(&options);
  options.horizon = 1.5 * 10 / 12;
  horizon_list* list = nullptr;
  ASSERT_EQ(horizon_search(points.xyz.data(), points.size(), 3, &options, &list), HORIZON_OK);
  // A disk in the plane x = 5 cuts bonds; the C++ filter gives the same list.
  const char* disk = R"([{"type": "disk", "center": [5, 5, 5], "normal": [1, 0, 0], "radius": 3}])";
  ASSERT_EQ(horizon_filter_bonds(list, points.xyz.data(), points.size(), 3, disk, 0), HORIZON_OK) << horizon_last_error();
  SearchOptions cpp;
  cpp.horizon = options.horizon;
  const NeighborList cut = filter_bonds(search(points.view(), cpp), points.view(), parse_bond_filters(disk, "disk"));
  EXPECT_LT(cut.total(), search(points.view(), cpp).total());
  std::vector<std::int32_t> blocks(points.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) blocks[i] = points.xyz[3 * i] < 5 ? 1 : 2;
  ASSERT_EQ(horizon_filter_blocks(list, blocks.data(), "1-1,2-2", 0), HORIZON_OK) << horizon_last_error();
  const NeighborList expected = filter_blocks(NeighborList(cut), blocks, BlockPairs::parse("1-1,2-2"));
  // One-based: every offset and id plus one, in place (the arrays are not reallocated).
  const std::int32_t* indices = horizon_list_indices(list);
  ASSERT_EQ(horizon_list_make_one_based(list), HORIZON_OK);
  EXPECT_EQ(horizon_list_indices(list), indices);
  EXPECT_TRUE(horizon_list_is_one_based(list));
  EXPECT_EQ(horizon_list_total(list), expected.total());
  for (std::size_t i = 0; i <= points.size(); ++i) ASSERT_EQ(horizon_list_offsets(list)[i], expected.offsets()[i] + 1);
  for (std::int64_t e = 0; e < expected.total(); ++e) ASSERT_EQ(indices[e], expected.indices()[e] + 1);
  EXPECT_EQ(horizon_filter_blocks(list, blocks.data(), "1-1", 0), HORIZON_INVALID_INPUT);
  EXPECT_NE(std::string(horizon_last_error()).find("one-based"), std::string::npos);
  horizon_list_free(list);

  // Verlet: refresh equals a fresh search until a point has moved skin / 2.
  horizon_verlet* verlet = nullptr;
  ASSERT_EQ(horizon_verlet_create(points.xyz.data(), points.size(), 3, &options, 0.2, &verlet), HORIZON_OK);
  std::vector<double> moved = points.xyz;
  for (std::size_t i = 0; i < moved.size(); i += 3) moved[i] += 0.09 * std::sin(static_cast<double>(i));
  int needed = -1;
  ASSERT_EQ(horizon_verlet_needs_rebuild(verlet, moved.data(), points.size(), &needed), HORIZON_OK);
  EXPECT_EQ(needed, 0);
  ASSERT_EQ(horizon_verlet_refresh(verlet, moved.data(), points.size(), &list), HORIZON_OK);
  EXPECT_EQ(take(list), search(PointView(moved.data(), points.size(), 3), cpp));
  for (std::size_t i = 0; i < moved.size(); i += 3) moved[i] += 0.2;
  ASSERT_EQ(horizon_verlet_needs_rebuild(verlet, moved.data(), points.size(), &needed), HORIZON_OK);
  EXPECT_EQ(needed, 1);
  horizon_verlet_free(verlet);
}

/// The status of a failed call, and that its message contains `cause`.
void expect_error(horizon_status status, horizon_status expected, const std::string& cause) {
  EXPECT_EQ(status, expected) << horizon_last_error();
  EXPECT_NE(std::string(horizon_last_error()).find(cause), std::string::npos) << "message: " << horizon_last_error();
}

TEST(CApi, EveryErrorReturnsItsCodeAndNamesTheCause) {
  std::vector<double> points = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  horizon_options options;
  horizon_options_default(&options);
  options.horizon = 1.5;
  horizon_list* list = reinterpret_cast<horizon_list*>(&options);  // set to NULL by every failed call

  points[4] = std::numeric_limits<double>::quiet_NaN();
  expect_error(horizon_search(points.data(), 3, 3, &options, &list), HORIZON_INVALID_INPUT, "point 1");
  EXPECT_EQ(list, nullptr);
  points[4] = 1;
  options.horizon = -1;
  expect_error(horizon_search(points.data(), 3, 3, &options, &list), HORIZON_INVALID_INPUT, "horizon");
  options.horizon = 1.5;
  options.backend = 7;
  expect_error(horizon_search(points.data(), 3, 3, &options, &list), HORIZON_INVALID_INPUT, "options.backend is 7");
  options.backend = HORIZON_BACKEND_AUTO;
  options.metric = -1;
  expect_error(horizon_search(points.data(), 3, 3, &options, &list), HORIZON_INVALID_INPUT, "options.metric is -1");
  options.metric = HORIZON_METRIC_L2;
  expect_error(horizon_search(nullptr, 3, 3, &options, &list), HORIZON_INVALID_INPUT, "points is NULL");
  expect_error(horizon_search(points.data(), 3, 4, &options, &list), HORIZON_INVALID_INPUT, "dims is 4");
  expect_error(horizon_search(points.data(), 3, 3, nullptr, &list), HORIZON_INVALID_INPUT, "options is NULL");
  expect_error(horizon_search(points.data(), 3, 3, &options, nullptr), HORIZON_INVALID_INPUT, "list is NULL");
  horizon_options unfilled{};
  expect_error(horizon_search(points.data(), 3, 3, &unfilled, &list), HORIZON_INVALID_INPUT, "horizon_options_default");
  options.horizon = 2;      // 4 entries
  options.max_memory = 8;   // bytes: they do not fit
  expect_error(horizon_search(points.data(), 3, 3, &options, &list), HORIZON_LIST_TOO_LARGE, "");
  options.horizon = 1.5;
  options.max_memory = 0;
  const std::vector<double> radii = {1, 0, 1};
  expect_error(horizon_search_radii(points.data(), 3, 3, radii.data(), HORIZON_RADIUS_GATHER, &options, &list),
               HORIZON_INVALID_INPUT, "radius");
  options.half = 1;
  const std::vector<double> good_radii = {1, 1, 1};
  expect_error(horizon_search_radii(points.data(), 3, 3, good_radii.data(), HORIZON_RADIUS_GATHER, &options, &list),
               HORIZON_INVALID_INPUT, "gather");
  options.half = 0;
  if (!horizon_backend_available(HORIZON_BACKEND_CUDA)) {
    options.backend = HORIZON_BACKEND_CUDA;
    expect_error(horizon_search(points.data(), 3, 3, &options, &list), HORIZON_BACKEND_UNAVAILABLE, "cuda");
    options.backend = HORIZON_BACKEND_AUTO;
    horizon_device_list* device_list = nullptr;
    expect_error(horizon_search_device(points.data(), 3, 3, &options, nullptr, &device_list),
                 HORIZON_BACKEND_UNAVAILABLE, "cuda");
  }
  ASSERT_EQ(horizon_search(points.data(), 3, 3, &options, &list), HORIZON_OK);
  EXPECT_STREQ(horizon_last_error(), "");
  expect_error(horizon_filter_bonds(list, points.data(), 3, 3, "[{\"type\": \"square\"}]", 0), HORIZON_INVALID_INPUT, "square");
  expect_error(horizon_filter_bonds(list, points.data(), 2, 3, "[]", 0), HORIZON_INVALID_INPUT, "2 points");
  const std::int32_t blocks[] = {1, 1, 2};
  expect_error(horizon_filter_blocks(list, blocks, "1-x", 0), HORIZON_INVALID_INPUT, "1-x");
  horizon_list_free(list);
  horizon_list_free(nullptr);  // as free(NULL)
  EXPECT_STREQ(horizon_version(), HORIZON_VERSION_STRING);
}

TEST(CApi, AnOlderCallersSmallerOptionsStructStillWorks) {
  // A caller built against a header whose struct ended after `device`: the rest keeps its defaults.
  std::vector<double> points = {0, 0, 0, 1, 0, 0};
  horizon_options options;
  horizon_options_default(&options);
  options.horizon = 1.5;
  options.box[0] = 1e-9;  // beyond the old size: must be ignored
  options.size = offsetof(horizon_options, reserved);
  horizon_list* list = nullptr;
  ASSERT_EQ(horizon_search(points.data(), 2, 3, &options, &list), HORIZON_OK) << horizon_last_error();
  EXPECT_EQ(horizon_list_total(list), 2);
  horizon_list_free(list);
}

TEST(CApi, DeviceSearchLeavesTheListOnTheGpu) {
  if (!horizon_backend_available(HORIZON_BACKEND_CUDA)) {
    const char* required = std::getenv("HORIZON_REQUIRE_GPU");
    if (required && std::string(required) == "1") FAIL() << "HORIZON_REQUIRE_GPU=1 but no usable GPU";
    GTEST_SKIP() << "no usable GPU";
  }
#if defined(HORIZON_WITH_CUDA)
  const PointSet points = random_cloud(20000, 3, 5);
  double* device_xyz = nullptr;
  ASSERT_EQ(cudaMalloc(&device_xyz, points.xyz.size() * sizeof(double)), cudaSuccess);
  cudaMemcpy(device_xyz, points.xyz.data(), points.xyz.size() * sizeof(double), cudaMemcpyHostToDevice);
  horizon_options options;
  horizon_options_default(&options);
  options.horizon = 0.6;
  horizon_device_list* list = nullptr;
  ASSERT_EQ(horizon_search_device(device_xyz, points.size(), 3, &options, nullptr, &list), HORIZON_OK) << horizon_last_error();
  SearchOptions cpp;
  cpp.horizon = 0.6;
  const NeighborList expected = search(points.view(), cpp);
  ASSERT_EQ(horizon_device_list_size(list), points.size());
  ASSERT_EQ(horizon_device_list_total(list), expected.total());
  std::vector<std::int64_t> offsets(points.size() + 1);
  std::vector<std::int32_t> indices(static_cast<std::size_t>(expected.total()));
  cudaMemcpy(offsets.data(), horizon_device_list_offsets(list), offsets.size() * sizeof(std::int64_t), cudaMemcpyDeviceToHost);
  cudaMemcpy(indices.data(), horizon_device_list_indices(list), indices.size() * sizeof(std::int32_t), cudaMemcpyDeviceToHost);
  EXPECT_TRUE(std::equal(offsets.begin(), offsets.end(), expected.offsets().begin()));
  EXPECT_TRUE(std::equal(indices.begin(), indices.end(), expected.indices().begin()));
  horizon_device_list_free(list);
  cudaFree(device_xyz);
#endif
}

}  // namespace
}  // namespace horizon::testing
