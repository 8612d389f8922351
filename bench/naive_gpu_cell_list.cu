#include "naive_gpu_cell_list.hpp"

#include <cub/cub.cuh>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace bench {
namespace {

void check(cudaError_t status, const char* what) {
  if (status != cudaSuccess) throw std::runtime_error(std::string(what) + ": " + cudaGetErrorString(status));
}

template <typename T>
T* allocate(std::size_t count, cudaStream_t stream) {
  void* p = nullptr;
  check(cudaMallocAsync(&p, (count ? count : 1) * sizeof(T), stream), "cudaMallocAsync");
  return static_cast<T*>(p);
}

struct Axis {
  const double* xyz;
  int axis;
  __host__ __device__ double operator()(std::int64_t i) const { return xyz[3 * i + axis]; }
};

struct Cells {
  double lo[3], side;
  int dims[3];
  __device__ int of(double v, int a) const {
    return min(max(static_cast<int>((v - lo[a]) / side), 0), dims[a] - 1);
  }
};

__global__ void keys_and_ids(const double* xyz, std::int64_t n, Cells g, int* keys, int* ids) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  keys[i] = g.of(xyz[3 * i], 0) + g.dims[0] * (g.of(xyz[3 * i + 1], 1) + g.dims[1] * g.of(xyz[3 * i + 2], 2));
  ids[i] = static_cast<int>(i);
}

__global__ void bounds_and_gather(const int* keys, const int* ids, const double* xyz, std::int64_t n, int* start,
                                  int* end, double* x, double* y, double* z) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= n) return;
  if (p == 0 || keys[p] != keys[p - 1]) start[keys[p]] = static_cast<int>(p);
  if (p == n - 1 || keys[p] != keys[p + 1]) end[keys[p]] = static_cast<int>(p + 1);
  const std::int64_t i = ids[p];
  x[p] = xyz[3 * i];
  y[p] = xyz[3 * i + 1];
  z[p] = xyz[3 * i + 2];
}

template <bool Fill>
__global__ void families(const double* x, const double* y, const double* z, const int* ids, const int* start,
                         const int* end, std::int64_t n, Cells g, double h2, std::int64_t* counts,
                         const std::int64_t* offsets, int* out) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= n) return;
  const double xi = x[p], yi = y[p], zi = z[p];
  const int cx = g.of(xi, 0), cy = g.of(yi, 1), cz = g.of(zi, 2);
  const int self = ids[p];
  std::int64_t found = 0;
  int* row = Fill ? out + offsets[self] : nullptr;
  for (int kz = max(cz - 1, 0); kz <= min(cz + 1, g.dims[2] - 1); ++kz)
    for (int ky = max(cy - 1, 0); ky <= min(cy + 1, g.dims[1] - 1); ++ky)
      for (int kx = max(cx - 1, 0); kx <= min(cx + 1, g.dims[0] - 1); ++kx) {
        const int c = kx + g.dims[0] * (ky + g.dims[1] * kz);
        for (int q = start[c]; q < end[c]; ++q) {
          const double dx = xi - x[q], dy = yi - y[q], dz = zi - z[q];
          if ((dx * dx + dy * dy) + dz * dz < h2 && q != p) {
            if (Fill) row[found] = ids[q];
            ++found;
          }
        }
      }
  if (!Fill) counts[self] = found;
}

unsigned blocks(std::int64_t n) { return static_cast<unsigned>((n + 255) / 256); }

}  // namespace

NaiveGpuResult naive_gpu_cell_list(const double* xyz, std::size_t count, double horizon) {
  const auto n = static_cast<std::int64_t>(count);
  cudaStream_t stream = nullptr;
  int device = 0;
  check(cudaGetDevice(&device), "cudaGetDevice");
  cudaMemPool_t pool;
  check(cudaDeviceGetDefaultMemPool(&pool, device), "cudaDeviceGetDefaultMemPool");
  std::uint64_t keep = UINT64_MAX;
  check(cudaMemPoolSetAttribute(pool, cudaMemPoolAttrReleaseThreshold, &keep), "cudaMemPoolSetAttribute");
  check(cudaDeviceSynchronize(), "sync");
  const auto clock = std::chrono::steady_clock::now();

  // Bounds: six reductions.
  double lo[3], hi[3];
  double* extremes = allocate<double>(6, stream);
  std::size_t temp_bytes = 0;
  const thrust::counting_iterator<std::int64_t> index(0);
  check(cub::DeviceReduce::Min(nullptr, temp_bytes, thrust::make_transform_iterator(index, Axis{xyz, 0}), extremes, n, stream), "reduce");
  void* temp = allocate<char>(temp_bytes, stream);
  for (int a = 0; a < 3; ++a) {
    const auto values = thrust::make_transform_iterator(index, Axis{xyz, a});
    check(cub::DeviceReduce::Min(temp, temp_bytes, values, extremes + a, n, stream), "min");
    check(cub::DeviceReduce::Max(temp, temp_bytes, values, extremes + 3 + a, n, stream), "max");
  }
  double host_extremes[6];
  check(cudaMemcpyAsync(host_extremes, extremes, sizeof(host_extremes), cudaMemcpyDeviceToHost, stream), "copy");
  check(cudaStreamSynchronize(stream), "sync");
  Cells g{};
  g.side = horizon;
  std::int64_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    lo[a] = host_extremes[a];
    hi[a] = host_extremes[3 + a];
    g.lo[a] = lo[a];
    g.dims[a] = static_cast<int>(std::floor((hi[a] - lo[a]) / horizon)) + 1;
    cells *= g.dims[a];
  }
  int bits = 1;
  while ((std::int64_t{1} << bits) < cells) ++bits;

  // Binning.
  int *keys = allocate<int>(count, stream), *sorted_keys = allocate<int>(count, stream);
  int *ids = allocate<int>(count, stream), *sorted_ids = allocate<int>(count, stream);
  keys_and_ids<<<blocks(n), 256, 0, stream>>>(xyz, n, g, keys, ids);
  std::size_t sort_bytes = 0;
  check(cub::DeviceRadixSort::SortPairs(nullptr, sort_bytes, keys, sorted_keys, ids, sorted_ids, n, 0, bits, stream), "sort");
  void* sort_temp = allocate<char>(sort_bytes, stream);
  check(cub::DeviceRadixSort::SortPairs(sort_temp, sort_bytes, keys, sorted_keys, ids, sorted_ids, n, 0, bits, stream), "sort");
  int *start = allocate<int>(static_cast<std::size_t>(cells), stream), *end = allocate<int>(static_cast<std::size_t>(cells), stream);
  check(cudaMemsetAsync(start, 0, cells * sizeof(int), stream), "memset");
  check(cudaMemsetAsync(end, 0, cells * sizeof(int), stream), "memset");
  double *x = allocate<double>(count, stream), *y = allocate<double>(count, stream), *z = allocate<double>(count, stream);
  bounds_and_gather<<<blocks(n), 256, 0, stream>>>(sorted_keys, sorted_ids, xyz, n, start, end, x, y, z);

  // Count, scan, fill.
  std::int64_t *counts = allocate<std::int64_t>(count + 1, stream), *offsets = allocate<std::int64_t>(count + 1, stream);
  const double h2 = horizon * horizon;
  families<false><<<blocks(n), 256, 0, stream>>>(x, y, z, sorted_ids, start, end, n, g, h2, counts, nullptr, nullptr);
  check(cudaMemsetAsync(counts + n, 0, sizeof(std::int64_t), stream), "memset");
  std::size_t scan_bytes = 0;
  check(cub::DeviceScan::ExclusiveSum(nullptr, scan_bytes, counts, offsets, n + 1, stream), "scan");
  void* scan_temp = allocate<char>(scan_bytes, stream);
  check(cub::DeviceScan::ExclusiveSum(scan_temp, scan_bytes, counts, offsets, n + 1, stream), "scan");
  std::int64_t entries = 0;
  check(cudaMemcpyAsync(&entries, offsets + n, sizeof(entries), cudaMemcpyDeviceToHost, stream), "copy");
  check(cudaStreamSynchronize(stream), "sync");
  int* list = allocate<int>(static_cast<std::size_t>(entries), stream);
  families<true><<<blocks(n), 256, 0, stream>>>(x, y, z, sorted_ids, start, end, n, g, h2, nullptr, offsets, list);
  check(cudaGetLastError(), "launch");
  check(cudaStreamSynchronize(stream), "sync");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();

  for (void* p : {static_cast<void*>(extremes), temp, static_cast<void*>(keys), static_cast<void*>(sorted_keys),
                  static_cast<void*>(ids), static_cast<void*>(sorted_ids), sort_temp, static_cast<void*>(start),
                  static_cast<void*>(end), static_cast<void*>(x), static_cast<void*>(y), static_cast<void*>(z),
                  static_cast<void*>(counts), static_cast<void*>(offsets), scan_temp, static_cast<void*>(list)})
    check(cudaFreeAsync(p, stream), "cudaFreeAsync");
  check(cudaStreamSynchronize(stream), "sync");
  return {entries, seconds};
}

}  // namespace bench
