#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// The count pass's verdicts, kept for the fill: bit i of a point's words says whether the i-th
// candidate of its stencil, in walk order ((2k+1)^2 runs of 2k+1 cells, dz outer, dy inner), is
// in its row. The fills then read bits instead of coordinates and test nothing again: the
// per-point fills visit only the hits, the per-cell fill stages ids only. One bit a candidate
// is about a fifth of the list's bytes at k = 1 (a sixth of a 3-D stencil's candidates are hits).
#include "device_index.cuh"

namespace horizon::detail {
namespace {

/// Candidates in the stencil of the point at sorted position p.
template <int D>
__device__ std::int64_t stencil_size(const DeviceIndexView& ix, std::int64_t p) {
  const std::int64_t cx = ix.grid.cell_of(ix.x[p], 0), cy = ix.grid.cell_of(ix.y[p], 1);
  const std::int64_t cz = D == 3 ? ix.grid.cell_of(ix.z[p], 2) : 0;
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  std::int64_t size = 0;
  for (int dz = -reach_z; dz <= reach_z; ++dz)
    for (int dy = -k; dy <= k; ++dy) {
      std::int64_t begin, end;
      ix.row(cx, cy + dy, cz + dz, begin, end);
      size += end - begin;
    }
  return size;
}

/// words[p] = 32-bit words of hit bits the point at sorted position p needs (none without a row).
template <int D>
__global__ void stencil_words(DeviceIndexView ix, std::int64_t* words) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= ix.n) return;
  words[p] = ix.has_row(ix.order[p]) ? (stencil_size<D>(ix, p) + 31) / 32 : 0;
}

/// Calls emit(id) for each neighbour of the point at sorted position p, in walk order, from
/// its hit bits `words`.
template <int D, typename Emit>
__device__ void walk_hits(const DeviceIndexView& ix, std::int64_t p, const unsigned* words, Emit emit) {
  const std::int64_t cx = ix.grid.cell_of(ix.x[p], 0), cy = ix.grid.cell_of(ix.y[p], 1);
  const std::int64_t cz = D == 3 ? ix.grid.cell_of(ix.z[p], 2) : 0;
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  int at = 0;  // stencil index of the run's first candidate
  for (int dz = -reach_z; dz <= reach_z; ++dz)
    for (int dy = -k; dy <= k; ++dy) {
      std::int64_t begin, end;
      ix.row(cx, cy + dy, cz + dz, begin, end);
      if (end == begin) continue;
      const point_id* id = ix.id + begin;
      const int stop = at + static_cast<int>(end - begin);
      for (int lo = at & ~31; lo < stop; lo += 32) {
        unsigned word = words[lo >> 5];
        if (lo < at) word &= ~0u << (at - lo);  // bits of the runs before
        if (stop - lo < 32) word &= (1u << (stop - lo)) - 1;  // bits of the runs after
        for (; word; word &= word - 1) emit(id[lo - at + __ffs(word) - 1]);
      }
      at = stop;
    }
}

/// Whether the i-th candidate of a stencil is a hit, by its words.
__device__ bool is_hit(const unsigned* words, int i) { return (__ldg(words + (i >> 5)) >> (i & 31)) & 1u; }

}  // namespace
}  // namespace horizon::detail
