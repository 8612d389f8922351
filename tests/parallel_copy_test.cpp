// The host copies of the CUDA backend's transfers (run here without a GPU): every byte lands,
// whatever the alignment of either side and wherever the 2 MB pieces fall.
#include "core/parallel_copy.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <numeric>
#include <vector>

namespace {

TEST(ParallelCopy, CopiesEveryByteAtAnyAlignmentAndSize) {
  constexpr std::size_t mib = std::size_t{1} << 20;
  std::vector<unsigned char> from(9 * mib + 512), to(9 * mib + 512);
  std::iota(from.begin(), from.end(), 0);  // wraps every 256 bytes: misplaced bytes show
  for (std::size_t size : {std::size_t{0}, std::size_t{1}, std::size_t{15}, std::size_t{64}, std::size_t{1000},
                           2 * mib - 3, 2 * mib, 2 * mib + 77, 9 * mib})
    for (std::size_t from_offset : {0, 1, 8, 37})
      for (std::size_t to_offset : {0, 3, 16, 250}) {
        std::fill(to.begin(), to.end(), 0xEE);
        horizon::detail::parallel_copy(to.data() + to_offset, from.data() + from_offset, size);
        for (std::size_t i = 0; i < to_offset; ++i) ASSERT_EQ(to[i], 0xEE);
        ASSERT_EQ(std::memcmp(to.data() + to_offset, from.data() + from_offset, size), 0) << "size " << size;
        for (std::size_t i = to_offset + size; i < to_offset + size + 64 && i < to.size(); ++i) ASSERT_EQ(to[i], 0xEE);
      }
}

TEST(ParallelCopy, HugePageAdviceKeepsTheData) {
  std::vector<std::int64_t> values(3 << 20);
  std::iota(values.begin(), values.end(), 0);
  horizon::detail::advise_huge_pages(values.data(), values.size() * sizeof(std::int64_t));
  horizon::detail::advise_huge_pages(values.data() + 1, 10);  // smaller than a huge page: nothing to advise
  for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], static_cast<std::int64_t>(i));
}

}  // namespace
