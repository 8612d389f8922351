#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// Periodic images made on the GPU from the uploaded points, the same as the CPU's
// (core/periodic_images.hpp): a count per point, a scan, then each point near a face writes its
// images after the points, with the id of the point it copies. Made on the host, they cost an
// H200's 16-core host 2.7 ms for 10^6 points, more than the whole GPU search at m = 1.5.
#include <cub/device/device_scan.cuh>

#include <limits>

#include "../../core/periodic_images.hpp"
#include "../../core/reference_search.hpp"
#include "device_memory.hpp"
#include "horizon/error.hpp"
#include "launch.cuh"

namespace horizon::detail {
namespace {

__global__ void count_images(const double* xyz, std::int64_t n, PeriodicBox box, std::int64_t* counts) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i < n) counts[i] = box.image_count(xyz + i * box.dims);
}

/// Images of point i at images[first[i] ...] (first: exclusive offsets), image_of their originals.
__global__ void write_images(const double* xyz, std::int64_t n, PeriodicBox box, const std::int64_t* first,
                             double* images, point_id* image_of) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i >= n || first[i + 1] == first[i]) return;
  const double* point = xyz + i * box.dims;
  double shift[26][3];
  const int count = box.image_shifts(point, shift);
  for (int k = 0; k < count; ++k) {
    for (int a = 0; a < box.dims; ++a) images[(first[i] + k) * box.dims + a] = point[a] + shift[k][a];
    image_of[first[i] + k] = static_cast<point_id>(i);
  }
}

/// *first = the smallest index of a point outside [0, period) on a periodic axis (n if none).
__global__ void first_outside(const double* xyz, std::int64_t n, PeriodicBox box, unsigned long long* first) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  if (!box.contains(xyz + i * box.dims)) atomicMin(first, static_cast<unsigned long long>(i));
}

/// The host search's check (validate_box) for points already on the GPU: the same error, naming
/// the first point outside the box.
void check_inside_box(const double* xyz, std::size_t n, int dims, const SearchOptions& options, cudaStream_t stream,
                      MemoryMeter& meter) {
  validate_box_shape(options, dims);
  DeviceArray<unsigned long long> first(1, meter);
  unsigned long long outside = n;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(first.get(), &outside, sizeof(outside), cudaMemcpyHostToDevice, stream));
  first_outside<<<blocks_for(n), block_size, 0, stream>>>(xyz, static_cast<std::int64_t>(n), PeriodicBox(options, dims),
                                                          first.get());
  check_launch("first_outside");
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&outside, first.get(), sizeof(outside), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  if (outside == n) return;
  double point[3];
  HORIZON_CUDA_CHECK(cudaMemcpy(point, xyz + outside * static_cast<std::size_t>(dims), dims * sizeof(double),
                                cudaMemcpyDeviceToHost));
  throw_outside_box("point", static_cast<std::int64_t>(outside), point, dims, options);
}

/// The n points at `points` followed by their periodic images (`images` of them), and the id
/// each image is found as.
struct PointsWithImages {
  DeviceArray<double> xyz;
  DeviceArray<point_id> image_of;
  std::size_t images;
};

PointsWithImages append_images_on_device(const double* points, std::size_t n, const PeriodicBox& box,
                                         cudaStream_t stream, MemoryMeter& meter) {
  DeviceArray<std::int64_t> counts(n, meter), first(n + 1, meter);
  count_images<<<blocks_for(n), block_size, 0, stream>>>(points, static_cast<std::int64_t>(n), box, counts.get());
  check_launch("count_images");
  HORIZON_CUDA_CHECK(cudaMemsetAsync(first.get(), 0, sizeof(std::int64_t), stream));
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, temp_bytes, counts.get(), first.get() + 1,
                                                   static_cast<std::int64_t>(n), stream));
  DeviceArray<char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp.get(), temp_bytes, counts.get(), first.get() + 1,
                                                   static_cast<std::int64_t>(n), stream));
  std::int64_t images = 0;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&images, first.get() + n, sizeof(images), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  if (static_cast<std::size_t>(images) + n >= static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error("the points and their periodic images must be fewer than 2^31 - 1");

  const auto dims = static_cast<std::size_t>(box.dims), total = n + static_cast<std::size_t>(images);
  PointsWithImages out{DeviceArray<double>(total * dims, meter),
                       DeviceArray<point_id>(static_cast<std::size_t>(images), meter), static_cast<std::size_t>(images)};
  HORIZON_CUDA_CHECK(
      cudaMemcpyAsync(out.xyz.get(), points, n * dims * sizeof(double), cudaMemcpyDeviceToDevice, stream));
  write_images<<<blocks_for(n), block_size, 0, stream>>>(points, static_cast<std::int64_t>(n), box, first.get(),
                                                         out.xyz.get() + n * dims, out.image_of.get());
  check_launch("write_images");
  return out;
}

}  // namespace
}  // namespace horizon::detail
