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

__global__ void sort_tiny_rows(point_id* rows, const std::int64_t* offsets, std::int64_t base,
                               std::int64_t row_count) {
  const std::int64_t r = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (r >= row_count) return;
  const std::int64_t length = offsets[r + 1] - offsets[r];
  if (length > thread_row) return;
  point_id* row = rows + (offsets[r] - base);
  for (int i = 1; i < length; ++i) {
    const point_id value = row[i];
    int j = i;
    for (; j > 0 && row[j - 1] > value; --j) row[j] = row[j - 1];
    row[j] = value;
  }
}

template <int Items>
__global__ void sort_short_rows(point_id* rows, const std::int64_t* offsets, std::int64_t base,
                                std::int64_t row_count) {
  using WarpSort = cub::WarpMergeSort<point_id, Items, 32>;
  __shared__ typename WarpSort::TempStorage temp[block_size / 32];
  const int warp = threadIdx.x / 32, lane = threadIdx.x % 32;
  const std::int64_t r = blockIdx.x * static_cast<std::int64_t>(block_size / 32) + warp;
  if (r >= row_count) return;
  const std::int64_t begin = offsets[r] - base, length = offsets[r + 1] - offsets[r];
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

__global__ void sort_long_rows(point_id* rows, const std::int64_t* offsets, std::int64_t base) {
  using BlockSort = cub::BlockMergeSort<point_id, block_size, block_items>;
  __shared__ typename BlockSort::TempStorage temp;
  const std::int64_t r = blockIdx.x;
  const std::int64_t begin = offsets[r] - base, length = offsets[r + 1] - offsets[r];
  if (length <= warp_row || length > block_row) return;  // uniform across the block
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

/// Sorts rows of up to block_row ids, each by the smallest unit that holds it.
void sort_rows_on_chip(point_id* rows, const std::int64_t* offsets, std::int64_t base,
                       std::int64_t row_count, std::int64_t longest, cudaStream_t stream) {
  const unsigned warp_blocks = blocks_for(static_cast<std::size_t>(row_count) * 32);
  sort_tiny_rows<<<blocks_for(static_cast<std::size_t>(row_count)), block_size, 0, stream>>>(rows, offsets, base, row_count);
  check_launch("sort_tiny_rows");
  if (longest > thread_row) {
    if (longest <= 64)
      sort_short_rows<2><<<warp_blocks, block_size, 0, stream>>>(rows, offsets, base, row_count);
    else if (longest <= 128)
      sort_short_rows<4><<<warp_blocks, block_size, 0, stream>>>(rows, offsets, base, row_count);
    else
      sort_short_rows<8><<<warp_blocks, block_size, 0, stream>>>(rows, offsets, base, row_count);
    check_launch("sort_short_rows");
  }
  if (longest > warp_row) {
    sort_long_rows<<<static_cast<unsigned>(row_count), block_size, 0, stream>>>(rows, offsets, base);
    check_launch("sort_long_rows");
  }
}

}  // namespace
}  // namespace horizon::detail
