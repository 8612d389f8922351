#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// The per-cell fill, from the count pass's hit bits (hit_bits.cuh). A block takes an occupied
// cell and stages the ids of its stencil in shared memory once (read coalesced: (2k+1)^2 runs
// of 2k+1 adjacent cells in 3-D), sorted by id with their walk-order index when rows are to be
// sorted; then a warp per point of the cell sweeps the staged candidates 32 at a time, looks up
// each one's bit, and stores each sweep's hits as one coalesced piece of the row. Every point
// of the cell reads the candidates in id order, so rows come out sorted without a sort per row,
// and the cell's points share one staging and one sort. When the count pass staged the stencil
// sorted too (PassArgs::bits_by_id), each point's bits are already in id order: the stage holds
// the sorted ids only and the warp stores each word's hits as they come. Stages hold 256, 1024 or 4096
// candidates; the dense cells of a clustered cloud, past 1024, take a second launch with the
// widest stage, so the other cells keep their blocks per SM. A stencil larger than every stage
// is swept from global memory instead, leaving its rows unsorted: their ids go to a.spilled,
// to be sorted after the fill.
// Measured against the per-point fill + row sort (Nsight Compute, H100, lattice n = 200,
// m = 3.015), when this kernel still tested the staged coordinates itself: 14.6 ms against
// 25.9 ms. For rows of up to 64, or cells of fewer than 8 points, the per-point kernels win
// (point_kernel.cuh).
#include <cub/block/block_radix_sort.cuh>

#include "device_index.cuh"
#include "hit_bits.cuh"
#include "stencil_runs.cuh"

namespace horizon::detail {
namespace {

constexpr int wide_stage = 8;     // items per thread of the stage: 1024 candidates
constexpr int widest_stage = 32;  // 4096 candidates, for dense cells
static_assert(cell_block * wide_stage == by_id_limit, "the stage that reads bits in id order holds them all");

template <int Items>
struct Stage {
  static constexpr int capacity = cell_block * Items;
  using Sort = cub::BlockRadixSort<point_id, cell_block, Items, point_id>;
  using SortIds = cub::BlockRadixSort<point_id, cell_block, Items>;
  union {
    typename Sort::TempStorage sort;  // used before the indices are written
    typename SortIds::TempStorage sort_ids;
    point_id index[capacity];  // walk-order index of the i-th staged candidate
  };
  point_id id[capacity];
  StencilRuns runs;
};

/// One warp sweeps `count` candidates for a point; `candidate(i, id)` names the i-th and says
/// whether it is a hit. Hits are stored at row[found...] in candidate order; returns the new `found`.
template <typename Candidate>
__device__ int sweep(int count, point_id* row, int found, Candidate candidate) {
  const int lane = threadIdx.x % 32;
  for (int i0 = 0; i0 < count; i0 += 32) {
    const int i = i0 + lane;
    point_id other = 0;
    const bool hit = i < count && candidate(i, other);
    const unsigned ballot = __ballot_sync(0xffffffffu, hit);
    if (hit) row[found + __popc(ballot & ((1u << lane) - 1))] = other;
    found += __popc(ballot);
  }
  return found;
}

/// Fills the rows of the cells whose stencil holds more than `narrower` candidates (a launch
/// with a smaller stage took the others); with `wider_follows`, those past this stage's
/// capacity are left to a launch with a larger one, else swept from global memory.
template <int D, bool Sorted, int Items>
__global__ void __launch_bounds__(cell_block) cell_families(DeviceIndexView ix, PassArgs a, int narrower,
                                                            bool wider_follows) {
  extern __shared__ __align__(16) unsigned char stage_memory[];  // sized at launch: 6, 9 or 34 KB
  Stage<Items>& s = *reinterpret_cast<Stage<Items>*>(stage_memory);
  const int warp = threadIdx.x / 32;
  const std::int64_t cells = *ix.cell_count;
  for (std::int64_t c = blockIdx.x; c < cells; c += gridDim.x) {
    std::int64_t b, e;
    cell_range(ix, c, cells, b, e);
    list_runs<D>(ix, b, s.runs);
    const int stencil = s.runs.size();
    const bool staged = stencil <= Stage<Items>::capacity;
    const bool by_id = Sorted && Items <= wide_stage && bits_by_id(a, stencil);
    if (stencil <= narrower || (wider_follows && !staged)) {  // another launch's cell (same for the block)
      __syncthreads();  // every thread has read the stencil before the next cell rewrites it
      continue;
    }
    if (staged && by_id) {
      if constexpr (Items <= wide_stage) {
        point_id keys[Items];
        for (int j = 0; j < Items; ++j) {
          const int i = j * cell_block + static_cast<int>(threadIdx.x);
          keys[j] = i < stencil ? ix.id[s.runs.position_of(i)] : static_cast<point_id>((1u << a.sort_bits) - 1);
        }
        typename Stage<Items>::SortIds(s.sort_ids).SortBlockedToStriped(keys, 0, a.sort_bits);
        for (int j = 0; j < Items; ++j) {
          const int i = j * cell_block + static_cast<int>(threadIdx.x);
          if (i < stencil) s.id[i] = keys[j];
        }
      }
      __syncthreads();
    } else if (staged) {
      if constexpr (Sorted) {
        point_id keys[Items], index[Items];
        for (int j = 0; j < Items; ++j) {
          const int i = j * cell_block + static_cast<int>(threadIdx.x);
          index[j] = i;
          keys[j] = i < stencil ? ix.id[s.runs.position_of(i)]
                                : static_cast<point_id>((1u << a.sort_bits) - 1);  // sorts after every id
        }
        typename Stage<Items>::Sort(s.sort).SortBlockedToStriped(keys, index, 0, a.sort_bits);
        __syncthreads();  // the sort's storage becomes the indices
        for (int j = 0; j < Items; ++j) {
          const int i = j * cell_block + static_cast<int>(threadIdx.x);
          if (i < stencil) {
            s.index[i] = index[j];
            s.id[i] = keys[j];
          }
        }
      } else {
        for (int i = threadIdx.x; i < stencil; i += cell_block) s.id[i] = ix.id[s.runs.position_of(i)];
      }
      __syncthreads();
    }
    for (std::int64_t p = b + warp; p < e; p += cell_warps) {
      const point_id self = ix.order[p];
      if (self >= ix.queries || self < a.first || self >= a.last) continue;
      const unsigned* words = a.bits + a.bit_offsets[p];
      point_id* row = a.out + (a.offsets[self] - a.base);
      if (by_id) {
        // The words are the sweeps' ballots already: store each one's hits at once.
        const int lane = threadIdx.x % 32;
        int found = 0;
        for (int w = 0; w * 32 < stencil; ++w) {
          const unsigned word = __ldg(words + w);
          if ((word >> lane) & 1u) row[found + __popc(word & ((1u << lane) - 1))] = s.id[w * 32 + lane];
          found += __popc(word);
        }
      } else if (staged) {
        sweep(stencil, row, 0, [&](int i, point_id& id) {
          id = s.id[i];
          return is_hit(words, Sorted ? s.index[i] : i);
        });
      } else {
        if (Sorted && a.spill_count && threadIdx.x % 32 == 0) a.spilled[atomicAdd(a.spill_count, 1u)] = self;
        int found = 0;
        for (int r = 0; r < s.runs.runs; ++r) {
          const std::int64_t begin = s.runs.begin[r];
          const int first = s.runs.prefix[r];
          found = sweep(s.runs.prefix[r + 1] - first, row, found, [&](int i, point_id& id) {
            id = ix.id[begin + i];
            return is_hit(words, first + i);
          });
        }
      }
    }
    __syncthreads();  // the stage is rewritten for the next cell
  }
}

/// Launches the per-cell fill over the occupied cells whose stencil holds more than
/// `narrower` candidates (see cell_families), with as many blocks as the GPU holds at once
/// (each takes cells in turn).
template <bool Sorted, int Items, int D>
void launch_cell_fill(const DeviceIndexView& ix, const PassArgs& args, cudaStream_t stream, int narrower = 0,
                      bool wider_follows = false) {
  const auto kernel = cell_families<D, Sorted, Items>;
  constexpr int bytes = sizeof(Stage<Items>);
  kernel<<<resident_blocks(kernel, cell_block, bytes, ix.n), cell_block, bytes, stream>>>(ix, args, narrower,
                                                                                          wider_follows);
  check_launch("cell_families");
}

}  // namespace
}  // namespace horizon::detail
