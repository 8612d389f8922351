#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// Sorting families on chip, after they are filled.
#include <cub/cub.cuh>

#include <climits>

#include "horizon/points.hpp"
#include "launch.cuh"

namespace horizon::detail {
namespace {

// Families are sorted on chip, by the smallest unit that holds them: a thread per row of up to
// 32 ids (insertion sort), a warp per row of up to 256 (cub::WarpMergeSort, 2-8 ids a lane), a
// block per row of up to 2048 (cub::BlockMergeSort). CUB's DeviceSegmentedSort, used first,
// took 0.59 s for the 8 M rows of ~120 ids of lattice n = 200, m = 3.015 on an H100, against
// 0.028 s to count and fill them; it remains the path for rows longer than 2048.

constexpr int thread_row = 32, warp_row = 256, block_items = 8, block_row = block_size * block_items;

struct IdLess {
  __device__ bool operator()(point_id a, point_id b) const { return a < b; }
};

/// The rows a sort pass takes: the r-th row of a batch, or, with `listed`, the row of the r-th
/// id in that list (the rows a staged fill could not stage and stored unsorted); `first` is the
/// batch's first id.
struct RowSet {
  const std::int64_t* offsets;  // the batch's offsets: row r is [offsets[r], offsets[r + 1]) - base
  std::int64_t base;
  std::int64_t count;  // rows, or the list's capacity
  const point_id* listed = nullptr;
  const unsigned* listed_count = nullptr;
  point_id first = 0;

  /// Whether row r exists; its place in the batch's buffer and its length.
  __device__ bool find(std::int64_t r, std::int64_t& begin, std::int64_t& length) const {
    if (r >= count || (listed && r >= *listed_count)) return false;
    const std::int64_t local = listed ? listed[r] - first : r;
    begin = offsets[local] - base;
    length = offsets[local + 1] - offsets[local];
    return true;
  }
};

__global__ void sort_tiny_rows(point_id* rows, RowSet set) {
  std::int64_t begin, length;
  if (!set.find(blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x, begin, length)) return;
  if (length > thread_row) return;
  point_id* row = rows + begin;
  for (int i = 1; i < length; ++i) {
    const point_id value = row[i];
    int j = i;
    for (; j > 0 && row[j - 1] > value; --j) row[j] = row[j - 1];
    row[j] = value;
  }
}

template <int Items>
__global__ void sort_short_rows(point_id* rows, RowSet set) {
  using WarpSort = cub::WarpMergeSort<point_id, Items, 32>;
  __shared__ typename WarpSort::TempStorage temp[block_size / 32];
  const int warp = threadIdx.x / 32, lane = threadIdx.x % 32;
  std::int64_t begin, length;
  if (!set.find(blockIdx.x * static_cast<std::int64_t>(block_size / 32) + warp, begin, length)) return;
  if (length <= thread_row || length > 32 * Items) return;  // uniform across the warp
  point_id keys[Items];
  for (int i = 0; i < Items; ++i) {
    const int at = lane * Items + i;
    keys[i] = at < length ? rows[begin + at] : INT_MAX;
  }
  WarpSort(temp[warp]).Sort(keys, IdLess());
  for (int i = 0; i < Items; ++i) {
    const int at = lane * Items + i;
    if (at < length) rows[begin + at] = keys[i];
  }
}

__global__ void sort_long_rows(point_id* rows, RowSet set) {
  using BlockSort = cub::BlockMergeSort<point_id, block_size, block_items>;
  __shared__ typename BlockSort::TempStorage temp;
  std::int64_t begin, length;
  if (!set.find(blockIdx.x, begin, length)) return;  // uniform across the block
  if (length <= warp_row || length > block_row) return;
  point_id keys[block_items];
  for (int i = 0; i < block_items; ++i) {
    const int at = threadIdx.x * block_items + i;
    keys[i] = at < length ? rows[begin + at] : INT_MAX;
  }
  BlockSort(temp).Sort(keys, IdLess());
  for (int i = 0; i < block_items; ++i) {
    const int at = threadIdx.x * block_items + i;
    if (at < length) rows[begin + at] = keys[i];
  }
}

/// Sorts the set's rows of up to block_row ids, each by the smallest unit that holds it;
/// `shortest` and `longest` bound their lengths.
void sort_rows_on_chip(point_id* rows, const RowSet& set, std::int64_t shortest, std::int64_t longest,
                       cudaStream_t stream) {
  if (set.count == 0) return;
  const unsigned warp_blocks = blocks_for(static_cast<std::size_t>(set.count) * 32);
  if (shortest <= thread_row) {
    sort_tiny_rows<<<blocks_for(static_cast<std::size_t>(set.count)), block_size, 0, stream>>>(rows, set);
    check_launch("sort_tiny_rows");
  }
  if (longest > thread_row && shortest <= warp_row) {
    if (longest <= 64)
      sort_short_rows<2><<<warp_blocks, block_size, 0, stream>>>(rows, set);
    else if (longest <= 128)
      sort_short_rows<4><<<warp_blocks, block_size, 0, stream>>>(rows, set);
    else
      sort_short_rows<8><<<warp_blocks, block_size, 0, stream>>>(rows, set);
    check_launch("sort_short_rows");
  }
  if (longest > warp_row) {
    sort_long_rows<<<static_cast<unsigned>(set.count), block_size, 0, stream>>>(rows, set);
    check_launch("sort_long_rows");
  }
}

}  // namespace
}  // namespace horizon::detail
