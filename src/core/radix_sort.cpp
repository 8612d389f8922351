#include "radix_sort.hpp"

#include <omp.h>

#include <algorithm>
#include <vector>

namespace horizon::detail {

void radix_sort_high_word(ScratchBuffer<std::uint64_t>& keys, int bits, int threads) {
  if (bits <= 0 || keys.size() < 2) return;
  const auto n = static_cast<std::int64_t>(keys.size());
  const int passes = (bits + 10) / 11;
  const int width = (bits + passes - 1) / passes;
  const std::int64_t buckets = std::int64_t{1} << width;
  const std::uint64_t mask = static_cast<std::uint64_t>(buckets - 1);
  ScratchBuffer<std::uint64_t> other(keys.size());
  std::vector<std::int64_t> places(static_cast<std::size_t>(std::max(1, threads) * buckets));
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = 32 + pass * width;
    const std::uint64_t* in = keys.data();
    std::uint64_t* out = other.data();
#pragma omp parallel num_threads(threads)
    {
      const std::int64_t team = omp_get_num_threads(), t = omp_get_thread_num();
      const std::int64_t first = n * t / team, last = n * (t + 1) / team;
      std::int64_t* mine = places.data() + t * buckets;
      std::fill(mine, mine + buckets, 0);
      for (std::int64_t i = first; i < last; ++i) ++mine[in[i] >> shift & mask];
#pragma omp barrier
#pragma omp single
      {  // digit-major, thread-minor: each thread's keys of a digit follow the earlier threads'
        std::int64_t at = 0;
        for (std::int64_t d = 0; d < buckets; ++d)
          for (std::int64_t u = 0; u < team; ++u) {
            const std::int64_t c = places[static_cast<std::size_t>(u * buckets + d)];
            places[static_cast<std::size_t>(u * buckets + d)] = at;
            at += c;
          }
      }
      for (std::int64_t i = first; i < last; ++i) out[mine[in[i] >> shift & mask]++] = in[i];
    }
    keys.swap(other);
  }
}

}  // namespace horizon::detail
