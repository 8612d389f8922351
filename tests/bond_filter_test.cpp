// Bond filters: exact hand-made crossings (edges, rims, ends on the plane, bonds in the plane),
// filter_bonds against a brute-force pass over the oracle's pairs, symmetry, and the JSON reader.
#include <cmath>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include "horizon/bond_filter.hpp"
#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/oracle.hpp"
#include "horizon/search.hpp"
#include "bond_filter_oracle.hpp"

namespace horizon {
namespace {

// The plane x = 2; the rectangle spans y in [0, 3] along the bottom and z in [-3, 0] along
// bottom x normal = (0, 1, 0) x (1, 0, 0) = (0, 0, -1).
const BondFilter rectangle = RectangleFilter{{1, 0, 0}, {2, 0, 0}, {0, 1, 0}, 3, 3};
const BondFilter disk = DiskFilter{{2, 0, 0}, {1, 0, 0}, 1};

bool cut(const BondFilter& f, std::array<double, 3> a, std::array<double, 3> b) { return cuts(f, a.data(), b.data()); }

TEST(BondFilter, RectangleConvention) {
  EXPECT_TRUE(cut(rectangle, {1, 1, -1}, {3, 1, -1}));     // through the middle
  EXPECT_TRUE(cut(rectangle, {3, 1, -1}, {1, 1, -1}));     // either direction
  EXPECT_TRUE(cut(rectangle, {1, 1, -1}, {2, 1, -1}));     // an end on the rectangle
  EXPECT_FALSE(cut(rectangle, {2, 1, -1}, {2, 2, -1}));    // lying in its plane
  EXPECT_TRUE(cut(rectangle, {1, 3, -1}, {3, 3, -1}));     // through the edge y = 3
  EXPECT_TRUE(cut(rectangle, {1, 0, 0}, {3, 0, 0}));       // through the corner
  EXPECT_FALSE(cut(rectangle, {1, 3.5, -1}, {3, 3.5, -1}));
  EXPECT_FALSE(cut(rectangle, {1, 1, 0.5}, {3, 1, 0.5}));  // z > 0: the side runs along -z
  EXPECT_TRUE(cut(rectangle, {1, 1, -3}, {3, 1, -3}));     // the far edge
  EXPECT_FALSE(cut(rectangle, {0, 1, -1}, {1.5, 1, -1}));  // ends before the plane
  EXPECT_TRUE(cut(rectangle, {1, 0, -1}, {3, 2, -1}));     // oblique, crossing at y = 1
}

TEST(BondFilter, DiskConvention) {
  EXPECT_TRUE(cut(disk, {1, 0.5, 0}, {3, 0.5, 0}));
  EXPECT_FALSE(cut(disk, {1, 1, 0}, {3, 1, 0}));  // the rim is outside
  EXPECT_TRUE(cut(disk, {1, 0, 0}, {2, 0, 0}));   // an end at the centre
  EXPECT_FALSE(cut(disk, {2, 0, 0}, {2, 0.5, 0}));  // in the plane
  EXPECT_FALSE(cut(disk, {1, 0, 2}, {3, 0, 2}));
}

TEST(BondFilter, FilteredListsMatchBruteForceAndStaySymmetric) {
  std::mt19937_64 rng(7);
  for (int dims : {2, 3}) {
    const PointSet points = random_cloud(3000, dims, 5);
    SearchOptions options;
    options.horizon = dims == 3 ? 1.0 : 0.4;
    for (int count : {1, 4, 10, 20, 64}) {  // 20, 64: in groups of 16
      const std::vector<BondFilter> filters = random_filters(rng, count, dims);
      for (bool half : {false, true}) {
        options.half = half;
        const NeighborList list = search(points.view(), options);
        const NeighborList filtered = filter_bonds(list, points.view(), filters);
        EXPECT_EQ(filtered, brute_force_filter(brute_force(points.view(), options), points, filters));
        EXPECT_LT(filtered.total(), list.total()) << "the filters should cut something";
        EXPECT_EQ(filtered, filter_bonds(list, points.view(), filters, 0, 1));  // one thread, no reach
        EXPECT_EQ(filtered, filter_bonds(list, points.view(), filters, bond_reach(options, dims)));
        if (!half)
          for (std::size_t i = 0; i < filtered.size(); ++i)
            for (point_id j : filtered.row(i)) {
              const auto row = filtered.row(static_cast<std::size_t>(j));
              EXPECT_TRUE(std::binary_search(row.begin(), row.end(), static_cast<point_id>(i))) << i << "-" << j;
            }
      }
    }
  }
}

// A lattice whose points lie on the shapes' edges, rims and planes: bonds through the edges
// (inside), the rim (outside) and lying in the plane take `cuts`, bonds through the middle the
// shortcut for ends deep within a shape; all as the brute force, far from the origin too.
TEST(BondFilter, LatticeBondsOnEdgesRimsAndPlanesMatchBruteForce) {
  for (double offset : {0.0, 1e6}) {
    const auto [points, filters] = shapes_on_lattice(offset);
    SearchOptions options;
    options.horizon = 1.8;  // bonds along axes, face and body diagonals
    for (bool half : {false, true}) {
      options.half = half;
      const NeighborList list = search(points.view(), options);
      const NeighborList expected = brute_force_filter(list, points, filters);
      EXPECT_LT(expected.total(), list.total());
      EXPECT_EQ(filter_bonds(list, points.view(), filters, options.horizon), expected) << "offset " << offset;
      EXPECT_EQ(filter_bonds(list, points.view(), filters, options.horizon, 1), expected) << "offset " << offset;
    }
  }
}

TEST(BondFilter, QueryListsAreFilteredAgainstTheReferences) {
  const PointSet references = random_cloud(2000, 3, 8), queries = random_cloud(300, 3, 9);
  SearchOptions options;
  options.horizon = 1.2;
  const std::vector<BondFilter> filters{rectangle, DiskFilter{{5, 5, 5}, {0, 0, 1}, 3}};
  const NeighborList list = search(queries.view(), references.view(), options);
  const NeighborList filtered = filter_bonds(list, queries.view(), references.view(), filters, options.horizon);
  std::size_t at = 0;
  for (std::size_t q = 0; q < list.size(); ++q) {
    std::vector<point_id> expected;
    for (point_id r : list.row(q)) {
      std::array<double, 3> a{}, b{};
      for (int d = 0; d < 3; ++d) a[d] = queries.xyz[3 * q + d], b[d] = references.xyz[3 * static_cast<std::size_t>(r) + d];
      if (!cuts(filters[0], a.data(), b.data()) && !cuts(filters[1], a.data(), b.data())) expected.push_back(r);
    }
    const auto row = filtered.row(q);
    EXPECT_TRUE(std::equal(row.begin(), row.end(), expected.begin(), expected.end())) << "query " << q;
    at += expected.size();
  }
  EXPECT_EQ(static_cast<std::size_t>(filtered.total()), at);
  EXPECT_THROW(filter_bonds(list, queries.view(), references.view(), std::vector<BondFilter>(65, disk)), Error);
}

class BondFilterJson : public ::testing::Test {
protected:
  std::string file(const std::string& text) {
    // Named by process and test: ctest runs this fixture's tests at once.
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    const auto path = std::filesystem::temp_directory_path() /
                      ("horizon_filters_" + std::to_string(::getpid()) + "_" + test + "_" + std::to_string(count_++) + ".json");
    std::ofstream(path) << text;
    written_.push_back(path);
    return path.string();
  }
  void TearDown() override {
    for (const auto& path : written_) std::filesystem::remove(path);
  }
  void expect_error(const std::string& text, const std::string& message) {
    try {
      read_bond_filters(file(text));
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  int count_ = 0;
  std::vector<std::filesystem::path> written_;
};

TEST_F(BondFilterJson, ReadsBothShapesAndNormalises) {
  const auto filters = read_bond_filters(file(R"([
    {"type": "rectangle", "normal": [2, 0, 0], "lower_left_corner": [2, 0, 0], "bottom_unit_vector": [0, 1, 0],
     "bottom_length": 3, "side_length": 3},
    {"type": "disk", "center": [2, 0, 0], "normal": [0, 0, 5], "radius": 1}])"));
  ASSERT_EQ(filters.size(), 2u);
  EXPECT_EQ(std::get<RectangleFilter>(filters[0]).normal, (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(std::get<DiskFilter>(filters[1]).normal, (std::array<double, 3>{0, 0, 1}));
}

TEST_F(BondFilterJson, NormalisesHugeVectorsWithoutOverflow) {
  const auto filters = read_bond_filters(file(
      R"([{"type": "disk", "center": [0, 0, 0], "normal": [1e300, 0, 1e300], "radius": 1}])"));
  const auto normal = std::get<DiskFilter>(filters[0]).normal;
  EXPECT_DOUBLE_EQ(normal[0], std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(normal[2], std::sqrt(0.5));
}

TEST_F(BondFilterJson, ErrorsNameTheFilterAndKey) {
  expect_error("[{\"type\": \"disk\"", "not valid JSON");
  expect_error("{}", "expected a JSON array");
  expect_error(R"([{"type": "disk", "center": [0, 0, 0], "radius": 1}])", "filter 0: missing key 'normal'");
  expect_error(R"([{"type": "disk", "center": [0, 0], "normal": [0, 0, 1], "radius": 1}])",
               "'center' must be an array of 3 numbers");
  expect_error(R"([{"type": "disk", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": -1}])",
               "'radius' must be finite and > 0");
  expect_error(R"([{"type": "disk", "center": [0, 0, 0], "normal": [0, 0, 0], "radius": 1}])", "zero vector");
  expect_error(R"([{"type": "disk", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": 1}, {"type": "plane"}])",
               "filter 1: 'type' must be \"rectangle\" or \"disk\"");
  expect_error(R"([{"type": "rectangle", "normal": [1, 0, 0], "lower_left_corner": [0, 0, 0],
                    "bottom_unit_vector": [1, 1, 0], "bottom_length": 1, "side_length": 1}])",
               "must be perpendicular");
  expect_error("[]x", "not valid JSON");
  // Found by the fuzzer: a number too large for a double escaped as nlohmann's out_of_range.
  expect_error("[1e99999]", "not valid JSON");
  EXPECT_THROW(read_bond_filters("/nonexistent/filters.json"), Error);
}

}  // namespace
}  // namespace horizon
