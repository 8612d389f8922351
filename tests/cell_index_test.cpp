// The cell sort: the same index on any thread count, each cell's points ascending by input id.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/radix_sort.hpp"
#include "datasets.hpp"
#include "horizon/cell_index.hpp"

namespace horizon {
namespace {

void expect_same_index(const CellIndex& a, const CellIndex& b) {
  ASSERT_EQ(a.occupied_cells(), b.occupied_cells());
  const auto n = static_cast<std::ptrdiff_t>(a.point_count() + CellIndex::padding);
  EXPECT_TRUE(std::equal(a.order().begin(), a.order().begin() + n, b.order().begin()));
  for (std::size_t c = 0; c < a.occupied_cells(); ++c) {
    EXPECT_EQ(a.points_of(c).begin, b.points_of(c).begin);
    EXPECT_EQ(a.points_of(c).end, b.points_of(c).end);
  }
  for (int axis = 0; axis < 3; ++axis)
    for (std::size_t p = 0; p < a.point_count(); ++p) ASSERT_EQ(a.coords(axis)[p], b.coords(axis)[p]);
}

TEST(CellIndex, AnyThreadCountGivesTheSerialSortStableById) {
  for (const int dims : {2, 3})
    for (auto& data : testing::datasets(dims))
      for (const int k : {1, 3}) {
        SCOPED_TRACE(data.name + " " + std::to_string(dims) + "-D k " + std::to_string(k));
        const Grid grid = Grid::fit(data.points.view(), data.horizon, k);
        const CellIndex serial(data.points.view(), grid, 1);
        for (std::size_t c = 0; c < serial.occupied_cells(); ++c) {
          const auto [first, last] = serial.points_of(c);
          EXPECT_TRUE(std::is_sorted(serial.order().begin() + first, serial.order().begin() + last));
        }
        for (const int threads : {2, 3, 7}) expect_same_index(serial, CellIndex(data.points.view(), grid, threads));
      }
}

TEST(RadixSort, SortsByTheHighWordKeepingTheLowWordsOrder) {
  // 23 cell bits (three passes of 8), many equal cells, on thread counts that split unevenly.
  std::mt19937_64 rng(5);
  ScratchBuffer<std::uint64_t> keys(100003);
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = (rng() % (rng() % 2 ? 7 : 1u << 23)) << 32 | i;
  std::vector<std::uint64_t> expected(keys.begin(), keys.end());
  std::stable_sort(expected.begin(), expected.end(), [](auto a, auto b) { return a >> 32 < b >> 32; });
  for (const int threads : {1, 2, 5}) {
    ScratchBuffer<std::uint64_t> sorted = keys;
    detail::radix_sort_high_word(sorted, 23, threads);
    EXPECT_TRUE(std::equal(sorted.begin(), sorted.end(), expected.begin())) << threads << " threads";
  }
}

}  // namespace
}  // namespace horizon
