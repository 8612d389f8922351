#include "transpose_rows.hpp"

#include <omp.h>

#include <algorithm>
#include <vector>

#include "parallel_scan.hpp"
#include "row_batches.hpp"

namespace horizon::detail {

namespace {

/// log2 of the columns per block: about 512 blocks, so that the first pass's writes stream into
/// few enough buckets and the second pass's writes stay within one block's rows.
int block_shift(std::int64_t n) {
  int shift = 6;
  while ((n >> shift) > 512) ++shift;
  return shift;
}

}  // namespace

/// Writing each i straight to its place in row j missed the cache on every entry when the ids
/// are spread over the points (0.9 s for 66 M entries on one core, clustered cloud). Instead,
/// a wave of rows is first bucketed by block of columns, then each block's bucket is placed;
/// the buckets of a block are read part by part and the parts hold consecutive rows, so every
/// row of the result receives its i's in ascending order.
void transpose_rows(const std::int64_t* offsets, const point_id* ids, std::int64_t n, int threads,
                    Buffer<std::int64_t>& out_offsets, Buffer<point_id>& out_ids, std::int64_t wave_entries) {
  const std::int64_t total = offsets[n];
  threads = std::max(threads, 1);
  // Each column's length, counted in up to 8 parts of the entries (a counter per part and point).
  const int parts = static_cast<int>(std::max<std::int64_t>(1, std::min<std::int64_t>({threads, 8, n})));
  ScratchBuffer<std::int32_t> counts(static_cast<std::size_t>(parts) * static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(static, 1) num_threads(parts) if (parts > 1)
  for (int t = 0; t < parts; ++t) {
    std::int32_t* count = counts.data() + static_cast<std::size_t>(t) * static_cast<std::size_t>(n);
    for (std::int64_t e = total * t / parts; e < total * (t + 1) / parts; ++e) ++count[ids[e]];
  }
  out_offsets.resize(static_cast<std::size_t>(n) + 1);
  out_offsets[0] = 0;
  ScratchBuffer<std::int64_t> place(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t j = 0; j < n; ++j) {
    std::int64_t length = 0;
    for (int t = 0; t < parts; ++t) length += counts[static_cast<std::size_t>(t) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)];
    out_offsets[static_cast<std::size_t>(j) + 1] = length;
  }
  inclusive_scan(out_offsets.data(), out_offsets.size(), threads);
  std::copy(out_offsets.begin(), out_offsets.end() - 1, place.begin());
  out_ids.resize(static_cast<std::size_t>(total));

  const int shift = block_shift(n);
  const std::int64_t blocks = ((n - 1) >> shift) + 1;
  // bucket[t * blocks + b]: the entries of block b in part t, then where part t writes the next.
  std::vector<std::int64_t> bucket(static_cast<std::size_t>(threads) * static_cast<std::size_t>(blocks));
  ScratchBuffer<std::uint64_t> scratch;  // (j << 32) | i
  for (std::int64_t first = 0, last; first < n; first = last) {
    last = static_cast<std::int64_t>(batch_end(offsets, static_cast<std::size_t>(n), static_cast<std::size_t>(first), wave_entries));
    const std::int64_t begin = offsets[first], entries = offsets[last] - begin;
    if (static_cast<std::int64_t>(scratch.size()) < entries) scratch.resize(static_cast<std::size_t>(entries));
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
      const int team = omp_get_num_threads(), t = omp_get_thread_num();
      // Part t: the rows starting in its share of the wave's entries.
      auto row_at = [&](int part) {
        if (part == 0) return first;
        if (part == team) return last;
        return std::lower_bound(offsets + first, offsets + last, begin + entries * part / team) - offsets;
      };
      const std::int64_t row_begin = row_at(t), row_end = row_at(t + 1);
      std::int64_t* mine = bucket.data() + static_cast<std::size_t>(t) * static_cast<std::size_t>(blocks);
      std::fill(mine, mine + blocks, 0);
      for (std::int64_t e = offsets[row_begin]; e < offsets[row_end]; ++e) ++mine[ids[e] >> shift];
#pragma omp barrier
#pragma omp single
      {
        std::int64_t at = 0;  // block-major, parts in order within a block
        for (std::int64_t b = 0; b < blocks; ++b)
          for (int part = 0; part < team; ++part) {
            std::int64_t& slot = bucket[static_cast<std::size_t>(part) * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(b)];
            const std::int64_t count = slot;
            slot = at;
            at += count;
          }
      }
      for (std::int64_t i = row_begin; i < row_end; ++i)
        for (std::int64_t e = offsets[i]; e < offsets[i + 1]; ++e) {
          const auto j = static_cast<std::uint64_t>(ids[e]);
          scratch[static_cast<std::size_t>(mine[j >> shift]++)] = j << 32 | static_cast<std::uint64_t>(i);
        }
#pragma omp barrier
      // Block b's bucket: from where the last part's bucket of block b - 1 ended.
      const std::int64_t* last_part = bucket.data() + static_cast<std::size_t>(team - 1) * static_cast<std::size_t>(blocks);
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t b = 0; b < blocks; ++b)
        for (std::int64_t s = b == 0 ? 0 : last_part[b - 1]; s < last_part[b]; ++s) {
          const std::uint64_t entry = scratch[static_cast<std::size_t>(s)];
          out_ids[static_cast<std::size_t>(place[entry >> 32]++)] = static_cast<point_id>(entry & 0xffffffffu);
        }
    }
  }
}

}  // namespace horizon::detail
