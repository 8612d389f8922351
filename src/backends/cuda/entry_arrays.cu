// A device list's entries as ASE's arrays, on the GPU: what a caller of ASE's conventions
// (python/horizon/atomistic.py with CUDA arrays) indexes with, without a round trip to the host.
#include <cuda_runtime.h>

#include "horizon/cuda.hpp"
#include "device_memory.hpp"
#include "launch.cuh"

namespace horizon {
namespace {

/// Entry e's row (the last row whose offset is at most e: a binary search, so that a primitive
/// cell's few long rows spread over as many threads as short rows do), its neighbour widened,
/// and its shift widened when there is one.
__global__ void widen_entries(const std::int64_t* offsets, std::int64_t rows, const point_id* indices,
                              const std::int32_t* shifts, int dims, std::int64_t total, std::int64_t* i,
                              std::int64_t* j, std::int64_t* wide_shifts) {
  const std::int64_t e = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (e >= total) return;
  std::int64_t low = 0, high = rows;  // offsets[low] <= e < offsets[high]
  while (high - low > 1) {
    const std::int64_t middle = low + (high - low) / 2;
    if (offsets[middle] <= e) low = middle;
    else high = middle;
  }
  i[e] = low;
  j[e] = indices[e];
  if (shifts)
    for (int a = 0; a < dims; ++a) wide_shifts[e * dims + a] = shifts[e * dims + a];
}

}  // namespace

DeviceEntryArrays entry_arrays(const DeviceNeighborList& list) {
  int device = 0;
  HORIZON_CUDA_CHECK(cudaGetDevice(&device));
  const cudaStream_t stream = list.stream();
  detail::MemoryMeter meter(device, stream);
  const auto total = static_cast<std::size_t>(list.total());
  const std::size_t shift_count = list.shifts() ? total * static_cast<std::size_t>(list.dims()) : 0;
  detail::DeviceArray<std::int64_t> i(total, meter), j(total, meter), shifts(shift_count, meter);
  if (total > 0) {
    widen_entries<<<detail::blocks_for(total), detail::block_size, 0, stream>>>(
        list.offsets(), static_cast<std::int64_t>(list.size()), list.indices(), list.shifts(), list.dims(),
        list.total(), i.get(), j.get(), shifts.get());
    detail::check_launch("widen_entries");
  }
  const DeviceNeighborList::Free free{stream};
  return DeviceEntryArrays{{i.release(), free}, {j.release(), free}, {shifts.release(), free}};
}

}  // namespace horizon
