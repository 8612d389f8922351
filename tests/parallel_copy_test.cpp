// The host copies of the CUDA backend's transfers (run here without a GPU): every byte lands,
// whatever the alignment of either side and wherever the 2 MB pieces fall.
#include "core/parallel_copy.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cstdint>
#include <cstring>
#include <numeric>
#include <vector>

#include "backends/cuda/staging_chunks.hpp"

namespace {

TEST(ParallelCopy, CopiesEveryByteAtAnyAlignmentAndSize) {
  constexpr std::size_t mib = std::size_t{1} << 20;
  std::vector<unsigned char> from(9 * mib + 512), to(9 * mib + 512);
  std::iota(from.begin(), from.end(), 0);  // wraps every 256 bytes: misplaced bytes show
  const int threads = omp_get_max_threads();
  // 16 threads: copies under 32 MB are cut into one piece per thread, not into 2 MB pieces.
  for (int copiers : {1, 3, 16}) {
    omp_set_num_threads(copiers);
    for (std::size_t size : {std::size_t{0}, std::size_t{1}, std::size_t{15}, std::size_t{64}, std::size_t{1000},
                             2 * mib - 3, 2 * mib, 2 * mib + 77, 9 * mib})
      for (std::size_t from_offset : {0, 1, 8, 37})
        for (std::size_t to_offset : {0, 3, 16, 250}) {
          std::fill(to.begin(), to.end(), 0xEE);
          horizon::detail::parallel_copy(to.data() + to_offset, from.data() + from_offset, size);
          for (std::size_t i = 0; i < to_offset; ++i) ASSERT_EQ(to[i], 0xEE);
          ASSERT_EQ(std::memcmp(to.data() + to_offset, from.data() + from_offset, size), 0)
              << "size " << size << ", " << copiers << " threads";
          for (std::size_t i = to_offset + size; i < to_offset + size + 64 && i < to.size(); ++i)
            ASSERT_EQ(to[i], 0xEE);
        }
  }
  omp_set_num_threads(threads);
}

TEST(StagingChunks, CoverTheCopyWithSmallEndsAndFullBuffersBetween) {
  constexpr std::size_t mib = std::size_t{1} << 20, largest = 64 * mib;
  for (std::size_t bytes : {std::size_t{0}, std::size_t{8}, mib, 3 * mib + 8, 24 * mib, 192 * mib, 571 * mib + 40,
                            5000 * mib}) {
    const auto chunks = horizon::detail::staging_chunks(bytes, largest);
    std::size_t at = 0;
    for (const auto& c : chunks) {
      ASSERT_EQ(c.at, at) << bytes;
      ASSERT_GT(c.size, 0u);
      ASSERT_LE(c.size, largest);
      ASSERT_EQ(c.size % 8, 0u) << "whole doubles and ids";
      at += c.size;
    }
    EXPECT_EQ(at, bytes);
    if (bytes >= 4 * mib) {
      EXPECT_EQ(chunks.front().size, 2 * mib) << bytes;
      EXPECT_EQ(chunks.back().size, 2 * mib) << bytes;
    }
    // Full buffers in the middle of a large copy: at most 14 chunks besides them.
    std::size_t full = 0;
    for (const auto& c : chunks) full += c.size == largest;
    if (bytes >= 1000 * mib) EXPECT_LE(chunks.size(), full + 14) << bytes;
  }
  // Staging smaller than the end chunk: every chunk is the staging's size or less.
  for (const auto& c : horizon::detail::staging_chunks(10 * mib, mib)) EXPECT_LE(c.size, mib);
}

TEST(ParallelCopy, HugePageAdviceKeepsTheData) {
  std::vector<std::int64_t> values(3 << 20);
  std::iota(values.begin(), values.end(), 0);
  horizon::detail::advise_huge_pages(values.data(), values.size() * sizeof(std::int64_t));
  horizon::detail::advise_huge_pages(values.data() + 1, 10);  // smaller than a huge page: nothing to advise
  for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], static_cast<std::int64_t>(i));
}

}  // namespace
