#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// The stencil of one occupied cell as the per-cell kernels see it: (2k+1)^2 runs of 2k+1
// adjacent cells in 3-D ((2k+1) in 2-D), each a range of sorted positions, listed once by the
// block; the i-th candidate of the stencil, in walk order, is found through the runs' prefix.
#include "device_index.cuh"

namespace horizon::detail {
namespace {

constexpr int cell_block = 128, cell_warps = cell_block / 32;
constexpr int most_runs = 49;  // (2k+1)^2 runs of a 3-D stencil, up to k = 3

struct StencilRuns {
  std::int64_t begin[most_runs];  // first sorted position of each run
  int prefix[most_runs + 1];      // candidates before each run; prefix[runs] = the stencil's size
  int runs;

  __device__ int size() const { return prefix[runs]; }

  /// Sorted position of the i-th candidate, in walk order.
  __device__ std::int64_t position_of(int i) const {
    int r = 0;
    while (prefix[r + 1] <= i) ++r;
    return begin[r] + (i - prefix[r]);
  }
};

/// Lists the runs of the stencil of the cell whose first sorted position is b: their lookups
/// on one thread each (independent loads), then their prefix on one thread. Called by every
/// thread of the block; the runs are ready when it returns.
template <int D>
__device__ void list_runs(const DeviceIndexView& ix, std::int64_t b, StencilRuns& s) {
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  const int runs = (2 * k + 1) * (2 * reach_z + 1);
  if (threadIdx.x < runs) {
    const int dy = static_cast<int>(threadIdx.x) % (2 * k + 1) - k;
    const int dz = static_cast<int>(threadIdx.x) / (2 * k + 1) - reach_z;
    const std::int64_t cx = ix.grid.cell_of(ix.x[b], 0), cy = ix.grid.cell_of(ix.y[b], 1);
    const std::int64_t cz = D == 3 ? ix.grid.cell_of(ix.z[b], 2) : 0;
    std::int64_t begin, end;
    ix.row(cx, cy + dy, cz + dz, begin, end);
    s.begin[threadIdx.x] = begin;
    s.prefix[threadIdx.x + 1] = static_cast<int>(end - begin);
  }
  __syncthreads();
  if (threadIdx.x == 0) {
    s.prefix[0] = 0;
    for (int r = 0; r < runs; ++r) s.prefix[r + 1] += s.prefix[r];
    s.runs = runs;
  }
  __syncthreads();
}

/// The occupied cell c's sorted positions [b, e).
__device__ void cell_range(const DeviceIndexView& ix, std::int64_t c, std::int64_t cells, std::int64_t& b,
                           std::int64_t& e) {
  b = ix.cell_first[c];
  e = c + 1 < cells ? ix.cell_first[c + 1] : ix.n;
}

/// Blocks of `threads` that a kernel taking cells in turn should launch: as many as the GPU
/// holds at once with `bytes` of dynamic shared memory each, at most one per point.
template <typename Kernel>
unsigned resident_blocks(Kernel kernel, int threads, int bytes, std::int64_t points) {
  int device = 0, processors = 0, per_processor = 0;
  HORIZON_CUDA_CHECK(cudaGetDevice(&device));
  HORIZON_CUDA_CHECK(cudaFuncSetAttribute(kernel, cudaFuncAttributeMaxDynamicSharedMemorySize, bytes));
  HORIZON_CUDA_CHECK(cudaDeviceGetAttribute(&processors, cudaDevAttrMultiProcessorCount, device));
  HORIZON_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_processor, kernel, threads, bytes));
  const std::int64_t most = std::max<std::int64_t>(1, points);
  return static_cast<unsigned>(std::min<std::int64_t>(most, std::int64_t{processors} * std::max(1, per_processor)));
}

}  // namespace
}  // namespace horizon::detail
