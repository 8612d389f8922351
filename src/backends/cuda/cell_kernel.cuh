#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// The per-cell fill, from the count pass's hit bits (hit_bits.cuh). A block takes an occupied
// cell and stages the ids of its stencil in shared memory once (read coalesced: (2k+1)^2 runs
// of 2k+1 adjacent cells in 3-D), sorted by id with their walk-order index when rows are to be
// sorted; then a warp per point of the cell sweeps the staged candidates 32 at a time, looks up
// each one's bit, and stores each sweep's hits as one coalesced piece of the row. Every point
// of the cell reads the candidates in id order, so rows come out sorted without a sort per row,
// and the cell's points share one staging and one sort. Stages hold 256, 1024 or 4096
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

namespace horizon::detail {
namespace {

constexpr int cell_block = 128, cell_warps = cell_block / 32;
constexpr int most_runs = 49;  // (2k+1)^2 runs of a 3-D stencil, up to k = 3
constexpr int wide_stage = 8;     // items per thread of the stage: 1024 candidates
constexpr int widest_stage = 32;  // 4096 candidates, for dense cells

template <int Items>
struct Stage {
  static constexpr int capacity = cell_block * Items;
  using Sort = cub::BlockRadixSort<point_id, cell_block, Items, point_id>;
  union {
    typename Sort::TempStorage sort;  // used before the indices are written
    point_id index[capacity];         // walk-order index of the i-th staged candidate
  };
  point_id id[capacity];
  std::int64_t run_begin[most_runs];
  int run_prefix[most_runs + 1];
  int runs;
};

/// Sorted position of the i-th candidate of the staged stencil.
template <int Items>
__device__ std::int64_t position_of(const Stage<Items>& s, int i) {
  int r = 0;
  while (s.run_prefix[r + 1] <= i) ++r;
  return s.run_begin[r] + (i - s.run_prefix[r]);
}

/// The occupied cell holding sorted position p (of the `cells` listed in ix.cell_first).
__device__ std::int64_t cell_at(const DeviceIndexView& ix, std::int64_t cells, std::int64_t p) {
  std::int64_t lo = 0, hi = cells;  // ix.cell_first[lo] <= p < ix.cell_first[hi]
  while (hi - lo > 1) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    if (ix.cell_first[mid] <= p) lo = mid;
    else hi = mid;
  }
  return lo;
}

/// One warp sweeps `count` candidates for a point; `candidate(i, id)` names the i-th and says
/// whether it is a hit. Hits are stored at row[found...] in candidate order; returns the new `found`.
/// Sweeps of 32 go four at a time where they can: their lookups (an id, an index, a word of
/// bits that depends on the index) are independent, so their latencies overlap.
template <typename Candidate>
__device__ int sweep(int count, point_id* row, int found, Candidate candidate) {
  constexpr int unroll = 4;
  const int lane = threadIdx.x % 32;
  const auto store = [&](bool hit, point_id other) {
    const unsigned ballot = __ballot_sync(0xffffffffu, hit);
    if (hit) row[found + __popc(ballot & ((1u << lane) - 1))] = other;
    found += __popc(ballot);
  };
  int i0 = 0;
  for (; i0 + 32 * unroll <= count; i0 += 32 * unroll) {
    point_id other[unroll];
    bool hit[unroll];
#pragma unroll
    for (int u = 0; u < unroll; ++u) hit[u] = candidate(i0 + 32 * u + lane, other[u]);
#pragma unroll
    for (int u = 0; u < unroll; ++u) store(hit[u], other[u]);
  }
  for (; i0 < count; i0 += 32) {
    const int i = i0 + lane;
    point_id other = 0;
    const bool hit = i < count && candidate(i, other);
    store(hit, other);
  }
  return found;
}

/// Fills the rows of ids [a.first, a.last) in the cells that meet sorted positions
/// [a.position_first, a.position_last) and whose stencil holds more than `narrower` candidates
/// (a launch with a smaller stage took the others); with `wider_follows`, those past this stage's
/// capacity are left to a launch with a larger one, else swept from global memory.
template <int D, bool Sorted, int Items>
__global__ void __launch_bounds__(cell_block) cell_families(DeviceIndexView ix, PassArgs a, int narrower,
                                                            bool wider_follows) {
  extern __shared__ __align__(16) unsigned char stage_memory[];  // sized at launch: 6, 9 or 34 KB
  Stage<Items>& s = *reinterpret_cast<Stage<Items>*>(stage_memory);
  const int warp = threadIdx.x / 32;
  const std::int64_t cells = *ix.cell_count;
  if (cells == 0 || a.position_last <= a.position_first) return;
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  const std::int64_t first_cell = cell_at(ix, cells, a.position_first);
  const std::int64_t end_cell = cell_at(ix, cells, a.position_last - 1) + 1;
  for (std::int64_t c = first_cell + blockIdx.x; c < end_cell; c += gridDim.x) {
    const std::int64_t b = ix.cell_first[c], e = c + 1 < cells ? ix.cell_first[c + 1] : ix.n;
    // The stencil's runs, one per thread (their lookups are independent loads), then their
    // prefix on one thread.
    const int runs = (2 * k + 1) * (2 * reach_z + 1);
    if (threadIdx.x < runs) {
      const int dy = static_cast<int>(threadIdx.x) % (2 * k + 1) - k, dz = static_cast<int>(threadIdx.x) / (2 * k + 1) - reach_z;
      const std::int64_t cx = ix.grid.cell_of(ix.x[b], 0), cy = ix.grid.cell_of(ix.y[b], 1);
      const std::int64_t cz = D == 3 ? ix.grid.cell_of(ix.z[b], 2) : 0;
      std::int64_t begin, end;
      ix.row(cx, cy + dy, cz + dz, begin, end);
      s.run_begin[threadIdx.x] = begin;
      s.run_prefix[threadIdx.x + 1] = static_cast<int>(end - begin);
    }
    __syncthreads();
    if (threadIdx.x == 0) {
      s.run_prefix[0] = 0;
      for (int r = 0; r < runs; ++r) s.run_prefix[r + 1] += s.run_prefix[r];
      s.runs = runs;
    }
    __syncthreads();
    const int stencil = s.run_prefix[s.runs];
    const bool staged = stencil <= Stage<Items>::capacity;
    if (stencil <= narrower || (wider_follows && !staged)) {  // another launch's cell (same for the block)
      __syncthreads();  // every thread has read the stencil before the next cell rewrites it
      continue;
    }
    if (staged) {
      if constexpr (Sorted) {
        point_id keys[Items], index[Items];
        for (int j = 0; j < Items; ++j) {
          const int i = j * cell_block + static_cast<int>(threadIdx.x);
          index[j] = i;
          keys[j] = i < stencil ? ix.id[position_of(s, i)]
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
        for (int i = threadIdx.x; i < stencil; i += cell_block) s.id[i] = ix.id[position_of(s, i)];
      }
      __syncthreads();
    }
    for (std::int64_t p = b + warp; p < e; p += cell_warps) {
      const point_id self = ix.order[p];
      if (!ix.has_row(self) || self < a.first || self >= a.last) continue;
      const unsigned* words = a.bits + a.bit_offsets[p];
      point_id* row = a.out + (a.offsets[self] - a.base);
      if (staged) {
        sweep(stencil, row, 0, [&](int i, point_id& id) {
          id = s.id[i];
          return is_hit(words, Sorted ? s.index[i] : i);
        });
      } else {
        if (Sorted && threadIdx.x % 32 == 0) a.spilled[atomicAdd(a.spill_count, 1u)] = self;
        int found = 0;
        for (int r = 0; r < s.runs; ++r) {
          const std::int64_t begin = s.run_begin[r];
          const int first = s.run_prefix[r];
          found = sweep(s.run_prefix[r + 1] - first, row, found, [&](int i, point_id& id) {
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
  int device = 0, processors = 0, per_processor = 0;
  HORIZON_CUDA_CHECK(cudaGetDevice(&device));
  HORIZON_CUDA_CHECK(cudaFuncSetAttribute(kernel, cudaFuncAttributeMaxDynamicSharedMemorySize, bytes));
  HORIZON_CUDA_CHECK(cudaDeviceGetAttribute(&processors, cudaDevAttrMultiProcessorCount, device));
  HORIZON_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_processor, kernel, cell_block, bytes));
  const std::int64_t most = std::max<std::int64_t>(1, args.position_last - args.position_first);
  const auto blocks = static_cast<unsigned>(std::min<std::int64_t>(most, std::int64_t{processors} * std::max(1, per_processor)));
  kernel<<<blocks, cell_block, bytes, stream>>>(ix, args, narrower, wider_follows);
  check_launch("cell_families");
}

}  // namespace
}  // namespace horizon::detail
