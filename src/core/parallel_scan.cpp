#include "parallel_scan.hpp"

#include <omp.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace horizon::detail {

void inclusive_scan(std::int64_t* data, std::size_t count, int threads) {
  constexpr std::size_t serial_below = std::size_t{1} << 18;
  if (threads <= 1 || count < serial_below) {
    std::partial_sum(data, data + count, data);
    return;
  }
  // Each thread sums its block, the block sums are scanned, then each block is scanned from
  // its predecessor's total.
  std::vector<std::int64_t> carry(static_cast<std::size_t>(threads) + 1, 0);
#pragma omp parallel num_threads(threads)
  {
    const auto blocks = static_cast<std::size_t>(omp_get_num_threads());
    const auto b = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t first = count * b / blocks, last = count * (b + 1) / blocks;
    carry[b + 1] = std::accumulate(data + first, data + last, std::int64_t{0});
#pragma omp barrier
#pragma omp single
    std::partial_sum(carry.begin(), carry.begin() + static_cast<std::ptrdiff_t>(blocks) + 1, carry.begin());
    std::int64_t sum = carry[b];
    for (std::size_t i = first; i < last; ++i) data[i] = sum += data[i];
  }
}

}  // namespace horizon::detail
