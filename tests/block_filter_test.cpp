// Block rules: filter_blocks against a brute-force pass over the search's pairs (full, half, a
// query list), the pair syntax, and the block ids read from .npy, text and Peridigm files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "horizon/block_filter.hpp"
#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/io.hpp"
#include "horizon/search.hpp"

namespace horizon {
namespace {

bool allowed(const BlockPairs& pairs, std::int32_t a, std::int32_t b) {
  for (const auto& [x, y] : pairs.pairs)
    if ((x == a && y == b) || (x == b && y == a)) return true;
  return false;
}

std::vector<std::int32_t> random_blocks(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::int32_t ids[] = {1, 2, 5};
  std::vector<std::int32_t> blocks(count);
  for (auto& b : blocks) b = ids[rng() % 3];
  return blocks;
}

void expect_filtered(const NeighborList& list, const NeighborList& filtered, const std::vector<std::int32_t>& rows,
                     const std::vector<std::int32_t>& columns, const BlockPairs& pairs) {
  ASSERT_EQ(filtered.size(), list.size());
  EXPECT_EQ(filtered.is_half(), list.is_half());
  std::int64_t kept = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::vector<point_id> expected;
    for (point_id j : list.row(i))
      if (allowed(pairs, rows[i], columns[static_cast<std::size_t>(j)])) expected.push_back(j);
    const auto row = filtered.row(i);
    ASSERT_TRUE(std::equal(row.begin(), row.end(), expected.begin(), expected.end())) << "row " << i;
    kept += static_cast<std::int64_t>(expected.size());
  }
  EXPECT_EQ(filtered.total(), kept);
  EXPECT_LT(kept, list.total());  // the pairs left some bonds out
}

TEST(BlockFilter, KeepsExactlyTheBondsOfThePairs) {
  const PointSet points = random_cloud(1500, 3, 8);
  const auto blocks = random_blocks(points.size(), 3);
  const BlockPairs pairs = BlockPairs::parse("1-1,5-2");
  for (bool half : {false, true})
    for (int threads : {1, 3}) {
      SearchOptions options;
      options.horizon = 1.2;
      options.half = half;
      const NeighborList list = search(points.view(), options);
      expect_filtered(list, filter_blocks(list, blocks, pairs, threads), blocks, blocks, pairs);
    }
  // Every pair allowed: the list unchanged.
  SearchOptions options;
  options.horizon = 1.2;
  const NeighborList list = search(points.view(), options);
  EXPECT_EQ(filter_blocks(list, blocks, BlockPairs::parse("1-1,1-2,1-5,2-2,2-5,5-5")), list);
}

TEST(BlockFilter, QueryListsUseTheReferencesBlocks) {
  const PointSet queries = random_cloud(300, 3, 4), references = random_cloud(1200, 3, 5);
  const auto row_blocks = random_blocks(queries.size(), 6), column_blocks = random_blocks(references.size(), 7);
  SearchOptions options;
  options.horizon = 1.3;
  const NeighborList list = search(queries.view(), references.view(), options);
  const BlockPairs pairs = BlockPairs::parse("2-2,1-5");
  expect_filtered(list, filter_blocks(list, row_blocks, column_blocks, pairs), row_blocks, column_blocks, pairs);
}

TEST(BlockFilter, ClearErrors) {
  for (const char* bad : {"1-", "a-b", "1-2,", "-1-2", "12", "1-2-3", ""})
    EXPECT_THROW(BlockPairs::parse(bad), Error) << bad;
  const PointSet points = random_cloud(100, 3, 1);
  SearchOptions options;
  options.horizon = 1.0;
  const NeighborList list = search(points.view(), options);
  const std::vector<std::int32_t> blocks(points.size(), 1);
  try {
    filter_blocks(list, blocks, BlockPairs::parse("1-1,1-3"));
    FAIL() << "a pair with an unknown block was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("block pair 1-3: no point is in block 3 (blocks: 1)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(filter_blocks(list, std::vector<std::int32_t>(5, 1), BlockPairs::parse("1-1")), Error);
}

class BlockFiles : public ::testing::Test {
protected:
  std::string file(const std::string& name, const std::string& bytes) {
    const auto path = std::filesystem::temp_directory_path() / ("horizon_blocks_" + name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path.string();
  }
  std::string error_of(const std::string& path, std::size_t points) {
    try {
      read_blocks(path, points);
    } catch (const Error& e) {
      return e.what();
    }
    return "accepted";
  }
};

TEST_F(BlockFiles, NpyTextAndPeridigm) {
  std::string header = "{'descr': '<i8', 'fortran_order': False, 'shape': (3,), }";
  while ((10 + header.size() + 1) % 64) header += ' ';
  header += '\n';
  const std::string values("\x01\0\0\0\0\0\0\0\x02\0\0\0\0\0\0\0\x07\0\0\0\0\0\0\0", 24);
  const std::string npy = std::string("\x93NUMPY\x01\x00", 8) + static_cast<char>(header.size()) + '\0' + header + values;
  EXPECT_EQ(read_blocks(file("b.npy", npy), 3), (std::vector<std::int32_t>{1, 2, 7}));
  EXPECT_NE(error_of(file("b.npy", npy), 4).find("3 block ids for 4 points"), std::string::npos);
  EXPECT_EQ(read_blocks(file("b.txt", "# blocks\n1\n2\n\n7\n"), 3), (std::vector<std::int32_t>{1, 2, 7}));
  EXPECT_NE(error_of(file("b.txt", "1\n2.5\n"), 2).find("b.txt:2: expected one block id"), std::string::npos);
  EXPECT_NE(error_of(file("b.txt", "1\n-2\n"), 2).find(":2:"), std::string::npos);
  const PointSet peridigm = read_points(file("p.txt", "# x y z block volume\n0 0 0 1 0.1\n1 0 0 2 0.1\n"));
  EXPECT_EQ(peridigm.blocks, (std::vector<std::int32_t>{1, 2}));
  EXPECT_TRUE(read_points(file("q.txt", "0 0 0\n1 0 0\n")).blocks.empty());
  EXPECT_THROW(read_points(file("r.txt", "0 0 0 1.5 0.1\n")), Error);
}

}  // namespace
}  // namespace horizon
