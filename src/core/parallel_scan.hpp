#pragma once
// Prefix sums on several threads: the cell table and the row offsets hold one entry per cell or
// point, and a serial scan of them is the longest serial step left at 16 threads.
#include <cstddef>
#include <cstdint>

namespace horizon::detail {

/// data[i] becomes data[0] + ... + data[i].
void inclusive_scan(std::int64_t* data, std::size_t count, int threads);

}  // namespace horizon::detail
