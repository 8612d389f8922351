#pragma once
// Lists built or moved a batch of whole rows at a time (the CPU's lists larger than memory,
// transposes in waves) cut their rows the same way.
#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace horizon::detail {

/// The end of the batch that starts at row `first`: the rows [first, last) holding at most
/// `entries` ids in all (offsets: the n + 1 row offsets), or row `first` alone when it is longer.
inline std::size_t batch_end(const std::int64_t* offsets, std::size_t n, std::size_t first, std::int64_t entries) {
  const std::int64_t* end = std::upper_bound(offsets + first + 1, offsets + n + 1, offsets[first] + entries);
  return std::max(static_cast<std::size_t>(end - offsets) - 1, first + 1);
}

}  // namespace horizon::detail
