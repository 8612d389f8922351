// The pools of large freed blocks: lists, and a search's working arrays.
#include "horizon/buffer.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace horizon {
namespace {

constexpr std::size_t mib = std::size_t{1} << 20;

TEST(Buffer, ReusesLargeFreedBlocksForListsOfAboutTheirSize) {
  release_cached_buffers();
  const std::int32_t* first = nullptr;
  {
    Buffer<std::int32_t> list(200 * mib / sizeof(std::int32_t));
    list.back() = 7;
    first = list.data();
  }
  const std::size_t block = detail::cached_buffer_bytes();
  EXPECT_GE(block, 200 * mib + 200 * mib / 16);  // taken a little larger than asked
  {
    Buffer<std::int32_t> longer(210 * mib / sizeof(std::int32_t));  // the next step's longer list
    EXPECT_EQ(longer.data(), first);
    EXPECT_EQ(detail::cached_buffer_bytes(), 0u);
  }
  {
    Buffer<std::int32_t> shorter(120 * mib / sizeof(std::int32_t));  // at least half the block
    EXPECT_EQ(shorter.data(), first);
  }
  EXPECT_EQ(detail::cached_buffer_bytes(), block);
  {
    Buffer<std::int32_t> small(80 * mib / sizeof(std::int32_t));  // under half: the block is freed
    EXPECT_EQ(detail::cached_buffer_bytes(), 0u);
  }
  {
    Buffer<std::int64_t> offsets(10 * mib);  // a search's two arrays are both kept
    Buffer<std::int32_t> indices(200 * mib / sizeof(std::int32_t));
    Buffer<std::int32_t> tiny(mib);  // below 32 MB: never kept
  }
  EXPECT_GE(detail::cached_buffer_bytes(), 280 * mib);
  EXPECT_LT(detail::cached_buffer_bytes(), 320 * mib);
  release_cached_buffers();
  EXPECT_EQ(detail::cached_buffer_bytes(), 0u);
}

TEST(Buffer, ReusesAFreedWorkingArrayForTheNextSearchsArrays) {
  release_cached_buffers();
  const double* first = nullptr;
  {
    ScratchBuffer<double> coords(mib);  // 8 MB: a cell index's coordinates along one axis
    coords.back() = 1;
    first = coords.data();
  }
  EXPECT_GE(detail::cached_buffer_bytes(), 8 * mib);
  {
    ScratchBuffer<double> again(mib + 1000);  // the next search's, a little longer
    EXPECT_EQ(again.data(), first);
    ScratchBuffer<double> other(mib);  // no second block held: a fresh one
    EXPECT_NE(other.data(), first);
    ScratchBuffer<char> small(mib / 2);  // below 1 MB: never kept
  }
  EXPECT_GE(detail::cached_buffer_bytes(), 16 * mib);
  EXPECT_LT(detail::cached_buffer_bytes(), 18 * mib);
  release_cached_buffers();
  EXPECT_EQ(detail::cached_buffer_bytes(), 0u);
}

std::vector<void*> released_blocks;

TEST(Buffer, TellsTheReleaseHookOfEveryBlockGivenBack) {
  release_cached_buffers();  // blocks of earlier tests go to the hook they were kept under
  const detail::BlockReleaseHook before = detail::set_block_release_hook([](void* b) { released_blocks.push_back(b); });
  released_blocks.clear();
  void* first = nullptr;
  void* second = nullptr;
  {
    Buffer<std::int32_t> list(64 * mib / sizeof(std::int32_t));
    first = list.data();
  }
  EXPECT_TRUE(released_blocks.empty());  // held by the pool, not given back
  {
    Buffer<std::int32_t> shorter(33 * mib / sizeof(std::int32_t));  // under half of the held block: it is freed
    second = shorter.data();
    ASSERT_EQ(released_blocks.size(), 1u);
    EXPECT_EQ(released_blocks[0], first);
  }
  {
    Buffer<std::int32_t> longer(64 * mib / sizeof(std::int32_t));  // the held one is too small: freed
    first = longer.data();
    ScratchBuffer<char> tiny(1000);  // below 1 MB: never told
  }
  ASSERT_EQ(released_blocks.size(), 2u);
  EXPECT_EQ(released_blocks[1], second);
  release_cached_buffers();
  ASSERT_EQ(released_blocks.size(), 3u);
  EXPECT_EQ(released_blocks[2], first);
  detail::set_block_release_hook(before);
}

}  // namespace
}  // namespace horizon
