#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// The per-point build kernels: a thread per point in sorted order (so a warp's points share
// most of their candidates, read through L1), walking the stencil's (2k+1)^2 runs of 2k+1
// cells. The count pass also reports the widest stencil, which decides the fill kernel, and
// keeps its verdicts as hit bits (hit_bits.cuh). Rows of up to 64 are filled from those bits:
// each thread stages its row in shared memory, sorts it there, and the warp stores its 32 rows
// one after another as coalesced pieces. Measured (Nsight Compute, H100, lattice n = 200,
// m = 1.5), before the bits: the fill storing straight to the list took 2.4 ms and a
// thread-per-row sort after it 3.1 ms. Without bits (they did not fit) fill_families tests
// the candidates again and the rows are sorted after it.
#include <climits>

#include "device_index.cuh"
#include "hit_bits.cuh"
#include "horizon/metric.hpp"
#include "launch.cuh"

namespace horizon::detail {
namespace {

constexpr int staged_row = 64;  // longest row the short-row fill takes

/// Threads per block of the short-row fill: 33 KB of staged rows either way (256 threads for
/// rows of up to 32, measured 10-20 % faster there than 128 for rows of up to 64).
constexpr int staged_block(int rows) { return rows <= 32 ? 256 : 128; }

/// Calls emit(other) for each neighbour of the point at sorted position p, in stencil order,
/// and records every verdict in `words` when given (hit_bits.cuh); returns the stencil's size.
/// (Tried: 32-bit indices from each run's base pointers and a moving mask for the verdicts:
/// 25 % more instructions, 8.1 ms against 7.0 for the count of lattice n = 200, m = 3.015, H200.)
template <Metric M, int D, bool Half, typename Emit>
__device__ int walk_stencil(const DeviceIndexView& ix, std::int64_t p, point_id self, double threshold, Emit emit,
                            unsigned* words = nullptr) {
  const double xi = ix.x[p], yi = ix.y[p], zi = ix.z[p];
  const point_id name = Half ? ix.id[p] : self;  // half lists compare names (a GPU part's: global ids)
  const std::int64_t cx = ix.grid.cell_of(xi, 0), cy = ix.grid.cell_of(yi, 1);
  const std::int64_t cz = D == 3 ? ix.grid.cell_of(zi, 2) : 0;
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  int stencil = 0;
  unsigned word = 0;  // the verdicts of the word being filled
  for (int dz = -reach_z; dz <= reach_z; ++dz)
    for (int dy = -k; dy <= k; ++dy) {
      std::int64_t begin, end;
      ix.row(cx, cy + dy, cz + dz, begin, end);
      for (std::int64_t q = begin; q < end; ++q, ++stencil) {
        const double d = metric_accumulate<M>(xi - ix.x[q], yi - ix.y[q], D == 3 ? zi - ix.z[q] : 0.0);
        const point_id other = ix.id[q];
        const bool hit = d < threshold && (Half ? other > name : q != p);
        if (hit) emit(other);
        if (words) {
          word |= static_cast<unsigned>(hit) << (stencil & 31);
          if ((stencil & 31) == 31) {
            words[stencil >> 5] = word;
            word = 0;
          }
        }
      }
    }
  if (words && (stencil & 31)) words[stencil >> 5] = word;
  return stencil;
}

/// Candidates the full-list count tests per iteration: their loads and tests are independent,
/// and the loop's bookkeeping (bounds, the word of verdicts) is paid once per group.
constexpr int count_group = 4;

/// The count pass's walk for full lists: every candidate of the stencil tested, the point itself
/// too (it is where it is: d = 0), whose verdict is taken out after the walk, so no candidate is
/// compared with the point's own position or id. Returns the stencil's size; sets `found` and,
/// when Bits, the hit bits at `words` (hit_bits.cuh).
template <Metric M, int D, bool Bits>
__device__ int count_stencil(const DeviceIndexView& ix, std::int64_t p, double threshold, int& found,
                             unsigned* words) {
  const double xi = ix.x[p], yi = ix.y[p], zi = ix.z[p];
  const std::int64_t cx = ix.grid.cell_of(xi, 0), cy = ix.grid.cell_of(yi, 1);
  const std::int64_t cz = D == 3 ? ix.grid.cell_of(zi, 2) : 0;
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  int stencil = 0, own = 0;  // own: the point's index in its stencil
  unsigned word = 0;         // the verdicts of the word being filled
  found = 0;
  for (int dz = -reach_z; dz <= reach_z; ++dz)
    for (int dy = -k; dy <= k; ++dy) {
      std::int64_t begin, end;
      ix.row(cx, cy + dy, cz + dz, begin, end);
      if (dz == 0 && dy == 0) own = stencil + static_cast<int>(p - begin);
      const double *x = ix.x + begin, *y = ix.y + begin, *z = ix.z + begin;
      const int length = static_cast<int>(end - begin);
      for (int j = 0; j < length; j += count_group) {
        unsigned group = 0;  // bit u: the verdict of candidate j + u
#pragma unroll
        for (int u = 0; u < count_group; ++u)
          if (u == 0 || j + u < length) {
            const double d = metric_accumulate<M>(xi - x[j + u], yi - y[j + u], D == 3 ? zi - z[j + u] : 0.0);
            group |= static_cast<unsigned>(d < threshold) << u;
          }
        found += __popc(group);
        const int taken = min(count_group, length - j), used = stencil & 31;  // used: bits of `word` filled
        if (Bits) {
          word |= group << used;
          if (used + taken >= 32) {  // the word is full (so used >= 32 - count_group > 0)
            words[stencil >> 5] = word;
            word = group >> (32 - used);
          }
        }
        stencil += taken;
      }
    }
  if (Bits) {
    if (stencil & 31) words[stencil >> 5] = word;
    words[own >> 5] &= ~(1u << (own & 31));
  }
  if (0.0 < threshold) --found;  // the point's own verdict (0 < horizon^2 unless it underflows)
  return stencil;
}

/// Count pass: counts[id] = |family| of every point, the widest stencil of the queries, the
/// number of rows longer than staged_row and, when a.bits is set, every point's hit bits.
template <Metric M, int D, bool Half>
__global__ void __launch_bounds__(block_size) count_families(DeviceIndexView ix, PassArgs a) {
  __shared__ unsigned long long widest, long_rows;
  if (threadIdx.x == 0) widest = long_rows = 0;
  __syncthreads();
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p < ix.n) {
    const point_id self = ix.order[p];
    int found = 0;
    if (ix.has_row(self)) {
      unsigned* words = a.bits ? a.bits + a.bit_offsets[p] : nullptr;
      int stencil;
      if constexpr (Half)
        stencil = walk_stencil<M, D, Half>(ix, p, self, a.threshold, [&](point_id) { ++found; }, words);
      else if (words)
        stencil = count_stencil<M, D, true>(ix, p, a.threshold, found, words);
      else
        stencil = count_stencil<M, D, false>(ix, p, a.threshold, found, nullptr);
      atomicMax(&widest, static_cast<unsigned long long>(stencil));
      if (found > staged_row) atomicAdd(&long_rows, 1ull);
    }
    a.counts[self] = found;
  }
  __syncthreads();
  if (threadIdx.x == 0) {
    atomicMax(a.widest, widest);
    if (long_rows) atomicAdd(a.long_rows, long_rows);
  }
}

/// Fill pass for any row length: each thread stores its row straight into the list, from its
/// hit bits, or without them testing its candidates again.
template <Metric M, int D, bool Half>
__global__ void fill_families(DeviceIndexView ix, PassArgs a) {
  const std::int64_t p = a.position_first + blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= a.position_last) return;
  const point_id self = ix.order[p];
  if (!ix.has_row(self) || self < a.first || self >= a.last) return;
  point_id* row = a.out + (a.offsets[self] - a.base);
  int found = 0;
  const auto store = [&](point_id other) { row[found++] = other; };
  if (a.bits) walk_hits<D>(ix, p, a.bits + a.bit_offsets[p], store);
  else walk_stencil<M, D, Half>(ix, p, self, a.threshold, store);
}

/// Fill pass for rows of up to Rows, from the hit bits: rows staged in shared memory (column
/// `lane` of the warp's tile, padded so that both the per-thread and the per-row accesses avoid
/// bank conflicts), sorted there by insertion when Sorted, stored by the warp row after row. A
/// longer row (a dense spot of a clustered cloud) is stored straight into the list and its id
/// appended to a.spilled, to be sorted afterwards (sort_rows_on_chip over those rows).
template <int D, bool Sorted, int Rows>
__global__ void __launch_bounds__(staged_block(Rows)) fill_short_rows(DeviceIndexView ix, PassArgs a) {
  constexpr int pitch = 33;  // rows[j * pitch + lane]: 32 lanes, +1 against bank conflicts
  __shared__ point_id tile[staged_block(Rows) / 32][Rows * pitch];
  const int lane = threadIdx.x % 32;
  point_id* rows = tile[threadIdx.x / 32];
  const std::int64_t p = a.position_first + blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  int found = 0;
  point_id self = 0;
  if (p < a.position_last) {
    self = ix.order[p];
    if (ix.has_row(self) && self >= a.first && self < a.last) {
      const unsigned* words = a.bits + a.bit_offsets[p];
      if (a.offsets[self + 1] - a.offsets[self] <= Rows) {
        walk_hits<D>(ix, p, words, [&](point_id other) { rows[found++ * pitch + lane] = other; });
        if (Sorted)
          for (int i = 1; i < found; ++i) {
            const point_id value = rows[i * pitch + lane];
            int j = i;
            for (; j > 0 && rows[(j - 1) * pitch + lane] > value; --j) rows[j * pitch + lane] = rows[(j - 1) * pitch + lane];
            rows[j * pitch + lane] = value;
          }
      } else {
        point_id* row = a.out + (a.offsets[self] - a.base);
        std::int64_t stored = 0;
        walk_hits<D>(ix, p, words, [&](point_id other) { row[stored++] = other; });
        if (Sorted) a.spilled[atomicAdd(a.spill_count, 1u)] = self;
      }
    }
  }
  __syncwarp();
  const std::int64_t start = found > 0 ? a.offsets[self] - a.base : 0;
  for (int owner = 0; owner < 32; ++owner) {
    const int length = __shfl_sync(0xffffffffu, found, owner);
    const std::int64_t at = __shfl_sync(0xffffffffu, start, owner);
#pragma unroll
    for (int j0 = 0; j0 < Rows; j0 += 32)  // length <= Rows: a fixed count of stores, no loop
      if (j0 + lane < length) a.out[at + j0 + lane] = rows[(j0 + lane) * pitch + owner];
  }
}

template <int D, int Rows>
void launch_short_rows(const DeviceIndexView& ix, const PassArgs& args, bool sorted, cudaStream_t stream) {
  constexpr int threads = staged_block(Rows);
  const std::int64_t positions = args.position_last - args.position_first;
  const auto blocks = static_cast<unsigned>((positions + threads - 1) / threads);
  if (blocks == 0) return;
  if (sorted) fill_short_rows<D, true, Rows><<<blocks, threads, 0, stream>>>(ix, args);
  else fill_short_rows<D, false, Rows><<<blocks, threads, 0, stream>>>(ix, args);
  check_launch("fill_short_rows");
}

}  // namespace
}  // namespace horizon::detail
