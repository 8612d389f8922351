// Sub-lists: the in-place selection (the filters' path for a list passed with std::move) against
// the copying one, on rows of every kind and thread counts whose chunks split rows unevenly.
#include "core/select_entries.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace horizon {
namespace {

/// Rows of 0..40 ids (some empty), ids 0..999.
NeighborList random_list(std::size_t rows, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Buffer<std::int64_t> offsets(rows + 1);
  Buffer<point_id> indices;
  offsets[0] = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    const auto size = static_cast<std::size_t>(rng() % 41);
    for (std::size_t e = 0; e < size; ++e) indices.push_back(static_cast<point_id>(rng() % 1000));
    offsets[i + 1] = static_cast<std::int64_t>(indices.size());
  }
  return NeighborList(std::move(offsets), std::move(indices), false);
}

TEST(SelectEntries, InPlaceEqualsTheCopyForEveryThreadCount) {
  const NeighborList list = random_list(5000, 1);
  // Rows kept whole (every 3rd), rows emptied (every 7th), the rest losing odd ids; the first
  // rows keep everything, so the first chunk does not move.
  auto whole = [](std::size_t i) { return i % 3 == 0 || i < 100; };
  auto keep = [](std::size_t i, point_id j) { return i % 7 != 0 && j % 2 == 0; };
  const NeighborList expected =
      detail::select_entries(list, [&](std::size_t i, point_id j) { return whole(i) || keep(i, j); }, 1);
  ASSERT_LT(expected.total(), list.total());
  for (const int threads : {1, 2, 3, 7, 16}) {
    const NeighborList selected = detail::select_entries(NeighborList(list), whole, keep, threads);
    EXPECT_EQ(selected, expected) << threads << " threads";
  }
}

// The copying selection on any thread count against a row-by-row one: rows of 40,000 ids
// (bits over many words), empty rows, rows losing everything.
TEST(SelectEntries, CopyEqualsARowByRowSelection) {
  NeighborList list = random_list(20000, 3);
  auto [offsets, indices] = std::move(list).release();
  for (const std::size_t row : {std::size_t{5}, std::size_t{9000}, std::size_t{9001}, std::size_t{19999}}) {
    const auto at = static_cast<std::ptrdiff_t>(offsets[row + 1]);
    const std::size_t longer = 40000;
    indices.insert(indices.begin() + at, longer, point_id{0});
    for (std::size_t e = 0; e < longer; ++e) indices[static_cast<std::size_t>(at) + e] = static_cast<point_id>((e * 7919) % 1000);
    for (std::size_t i = row + 1; i < offsets.size(); ++i) offsets[i] += static_cast<std::int64_t>(longer);
  }
  list = NeighborList(std::move(offsets), std::move(indices), false);
  auto keep = [](std::size_t i, point_id j) { return i % 11 != 0 && (j % 3 != 0 || i % 5 == 0); };
  Buffer<std::int64_t> expected_offsets(list.size() + 1);
  Buffer<point_id> expected_indices;
  expected_offsets[0] = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    for (const point_id j : list.row(i))
      if (keep(i, j)) expected_indices.push_back(j);
    expected_offsets[i + 1] = static_cast<std::int64_t>(expected_indices.size());
  }
  const NeighborList expected(std::move(expected_offsets), std::move(expected_indices), false);
  for (const int threads : {1, 2, 3, 7, 16}) EXPECT_EQ(detail::select_entries(list, keep, threads), expected) << threads << " threads";
}

TEST(SelectEntries, InPlaceKeepsAListThatLosesNothing) {
  const NeighborList list = random_list(1000, 2);
  const NeighborList selected = detail::select_entries(
      NeighborList(list), [](std::size_t) { return false; }, [](std::size_t, point_id) { return true; }, 4);
  EXPECT_EQ(selected, list);
  const NeighborList emptied = detail::select_entries(
      NeighborList(list), [](std::size_t) { return false; }, [](std::size_t, point_id) { return false; }, 4);
  EXPECT_EQ(emptied.total(), 0);
  EXPECT_EQ(emptied.size(), list.size());
}

// Rows that shrank moved to their new offsets, against memmoves row by row: 4 * 10^6 entries
// (several waves), the first rows not moving, shifts from a few entries (saved where another
// part writes) to more than a wave, emptied rows, any thread count.
TEST(SelectEntries, MovesShrunkRowsDownAsMemmovesRowByRowWould) {
  std::mt19937_64 rng(5);
  const std::int64_t n = 200000;
  std::vector<std::int64_t> from(n + 1), to(n + 1);
  for (std::int64_t i = 0; i < n; ++i) {
    const auto length = static_cast<std::int64_t>(rng() % 41);
    const std::int64_t kept = i < 1000 ? length : i % 97 == 0 ? 0
                             : i < n / 2   ? length - static_cast<std::int64_t>(rng() % (length / 8 + 1))
                                           : length / 3;
    from[i + 1] = from[i] + length;
    to[i + 1] = to[i] + kept;
  }
  std::vector<point_id> data(static_cast<std::size_t>(from[n]));
  for (std::size_t e = 0; e < data.size(); ++e) data[e] = static_cast<point_id>(e);
  std::vector<point_id> expected = data;
  for (std::int64_t i = 0; i < n; ++i)
    std::memmove(expected.data() + to[i], expected.data() + from[i], static_cast<std::size_t>(to[i + 1] - to[i]) * sizeof(point_id));
  expected.resize(static_cast<std::size_t>(to[n]));
  ASSERT_GT(from[n] - to[n], std::int64_t{1} << 20) << "the largest shift should pass a wave";
  for (const int threads : {1, 2, 3, 7, 16}) {
    std::vector<point_id> moved = data;
    detail::move_rows_down(moved.data(), from.data(), to.data(), n, threads);
    moved.resize(static_cast<std::size_t>(to[n]));
    EXPECT_EQ(moved, expected) << threads << " threads";
  }
}

}  // namespace
}  // namespace horizon
