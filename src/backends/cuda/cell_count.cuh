#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// The count pass, a cell at a time: a block stages the stencil of an occupied cell in shared
// memory once (ids and coordinates; in walk order, or sorted by id when the fill will read the
// bits in id order, hit_bits.cuh), then a warp takes each point of the cell and its 32 lanes
// test 32 staged candidates at once: the warp's ballot is the point's next word of hit bits,
// and its population count adds to the family's size. Control flow stays uniform in the warp
// and the loop carries no per-candidate bookkeeping, where a thread per point walking its own
// stencil spent ~38 instructions a candidate (H200, lattice n = 200, m = 3.015). A stencil
// wider than the stage is swept run by run from global memory, in walk order.
#include <cub/block/block_radix_sort.cuh>

#include "hit_bits.cuh"
#include "horizon/metric.hpp"
#include "point_kernel.cuh"
#include "stencil_runs.cuh"

namespace horizon::detail {
namespace {

template <int D, int Items>
struct CountStage {
  static constexpr int capacity = cell_block * Items;
  using Sort = cub::BlockRadixSort<point_id, cell_block, Items, int>;
  StencilRuns runs;
  union {
    typename Sort::TempStorage sort;  // used before the coordinates are written
    double xyz[D][capacity];
  };
  point_id id[capacity];
};

/// The test of one candidate against the point (xi, yi, zi) whose id is self. The only other
/// candidates that share self's id are its periodic images, which lie at least a box length
/// (over twice the horizon) away, so comparing ids excludes the point from its own row.
template <Metric M, int D, bool Half>
__device__ bool is_neighbour(double xi, double yi, double zi, point_id self, double x, double y, double z,
                             point_id other, double threshold) {
  const double d = metric_accumulate<M>(xi - x, yi - y, D == 3 ? zi - z : 0.0);
  return d < threshold && (Half ? other > self : other != self);
}

/// Stages the stencil's ids and coordinates, in walk order or (by_id) sorted by id.
template <int D, int Items>
__device__ void stage_stencil(const DeviceIndexView& ix, const PassArgs& a, CountStage<D, Items>& s, bool by_id) {
  const double* axis[3] = {ix.x, ix.y, ix.z};
  const int stencil = s.runs.size();
  if (!by_id) {
    for (int i = threadIdx.x; i < stencil; i += cell_block) {
      const std::int64_t q = s.runs.position_of(i);
      s.id[i] = ix.id[q];
      for (int d = 0; d < D; ++d) s.xyz[d][i] = axis[d][q];
    }
    return;
  }
  point_id keys[Items];
  int index[Items];
  for (int j = 0; j < Items; ++j) {
    const int i = j * cell_block + static_cast<int>(threadIdx.x);
    index[j] = i;
    keys[j] = i < stencil ? ix.id[s.runs.position_of(i)]
                          : static_cast<point_id>((1u << a.sort_bits) - 1);  // sorts after every id
  }
  typename CountStage<D, Items>::Sort(s.sort).SortBlockedToStriped(keys, index, 0, a.sort_bits);
  __syncthreads();  // the sort's storage becomes the coordinates
  for (int j = 0; j < Items; ++j) {
    const int i = j * cell_block + static_cast<int>(threadIdx.x);
    if (i < stencil) {
      const std::int64_t q = s.runs.position_of(index[j]);
      s.id[i] = keys[j];
      for (int d = 0; d < D; ++d) s.xyz[d][i] = axis[d][q];
    }
  }
}

/// Count pass (and hit bits, when a.bits is set): counts[id] = |family| of every point, the
/// widest stencil of the queries and the number of rows longer than staged_row. With
/// a.bits_by_id the launch must stage at least by_id_limit candidates.
template <Metric M, int D, bool Half, int Items>
__global__ void __launch_bounds__(cell_block) count_cells(DeviceIndexView ix, PassArgs a) {
  extern __shared__ __align__(16) unsigned char stage_memory[];
  auto& s = *reinterpret_cast<CountStage<D, Items>*>(stage_memory);
  __shared__ unsigned long long widest, long_rows;
  if (threadIdx.x == 0) widest = long_rows = 0;
  __syncthreads();
  const int warp = threadIdx.x / 32, lane = threadIdx.x % 32;
  const std::int64_t cells = *ix.cell_count;
  unsigned long long my_widest = 0, my_long_rows = 0;  // lane 0's, for the warp's points
  for (std::int64_t c = blockIdx.x; c < cells; c += gridDim.x) {
    std::int64_t b, e;
    cell_range(ix, c, cells, b, e);
    list_runs<D>(ix, b, s.runs);
    const int stencil = s.runs.size();
    const bool staged = stencil <= CountStage<D, Items>::capacity;
    if (staged) stage_stencil(ix, a, s, bits_by_id(a, stencil));
    __syncthreads();
    for (std::int64_t p = b + warp; p < e; p += cell_warps) {
      const point_id self = ix.order[p];
      int found = 0;
      if (self < ix.queries) {
        const double xi = ix.x[p], yi = ix.y[p], zi = D == 3 ? ix.z[p] : 0.0;
        WordWriter out{a.bits ? a.bits + a.bit_offsets[p] : nullptr};
        if (staged) {
          for (int i0 = 0; i0 < stencil; i0 += 32) {
            const int i = i0 + lane;
            const bool hit = i < stencil && is_neighbour<M, D, Half>(xi, yi, zi, self, s.xyz[0][i], s.xyz[1][i],
                                                                     D == 3 ? s.xyz[D - 1][i] : 0.0, s.id[i],
                                                                     a.threshold);
            const unsigned word = __ballot_sync(0xffffffffu, hit);
            found += __popc(word);
            out.put(word);
          }
        } else {
          // Run by run from global memory; a run's verdicts continue the previous run's word.
          unsigned long long pending = 0;
          int pending_bits = 0;
          for (int r = 0; r < s.runs.runs; ++r) {
            const std::int64_t begin = s.runs.begin[r];
            const int length = s.runs.prefix[r + 1] - s.runs.prefix[r];
            for (int i0 = 0; i0 < length; i0 += 32) {
              const std::int64_t q = begin + i0 + lane;
              const bool hit = i0 + lane < length &&
                               is_neighbour<M, D, Half>(xi, yi, zi, self, ix.x[q], ix.y[q], D == 3 ? ix.z[q] : 0.0,
                                                        ix.id[q], a.threshold);
              const unsigned word = __ballot_sync(0xffffffffu, hit);
              found += __popc(word);
              pending |= static_cast<unsigned long long>(word) << pending_bits;
              pending_bits += min(32, length - i0);
              if (pending_bits >= 32) {
                out.put(static_cast<unsigned>(pending));
                pending >>= 32;
                pending_bits -= 32;
              }
            }
          }
          if (pending_bits > 0) out.put(static_cast<unsigned>(pending));
        }
        out.finish();
        my_widest = max(my_widest, static_cast<unsigned long long>(stencil));
        if (found > staged_row) ++my_long_rows;
      }
      if (lane == 0) a.counts[self] = found;
    }
    __syncthreads();  // the stage is rewritten for the next cell
  }
  if (lane == 0) {
    atomicMax(&widest, my_widest);
    if (my_long_rows) atomicAdd(&long_rows, my_long_rows);
  }
  __syncthreads();
  if (threadIdx.x == 0) {
    atomicMax(a.widest, widest);
    if (long_rows) atomicAdd(a.long_rows, long_rows);
  }
}

/// Launches the count pass over the occupied cells, as many blocks as the GPU holds at once.
template <Metric M, int D, bool Half, int Items>
void launch_count_cells(const DeviceIndexView& ix, const PassArgs& args, cudaStream_t stream) {
  const auto kernel = count_cells<M, D, Half, Items>;
  constexpr int bytes = sizeof(CountStage<D, Items>);
  kernel<<<resident_blocks(kernel, cell_block, bytes, ix.n), cell_block, bytes, stream>>>(ix, args);
  check_launch("count_cells");
}

}  // namespace
}  // namespace horizon::detail
