#pragma once
// A stable sort of 64-bit keys by their high word on several threads, for the cell sort: a key
// is (cell << 32 | point), so equal cells keep their points in input order without a lock or a
// per-cell sort (the atomic counting sort it replaced took 0.06 s for 10^6 clustered points on
// 16 threads, contending on the dense cells).
#include <cstdint>

#include "horizon/buffer.hpp"

namespace horizon::detail {

/// Sorts `keys` by bits [32, 32 + bits) on `threads` threads, stably (least significant digit
/// first, up to 11 bits per pass, one histogram per thread).
void radix_sort_high_word(ScratchBuffer<std::uint64_t>& keys, int bits, int threads);

}  // namespace horizon::detail
