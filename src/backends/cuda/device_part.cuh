#pragma once
// Included at the end of search.cu only (it uses the host path's stream pool, upload and
// staging): a part of a multi-GPU search whose list stays on its GPU (core/device_part.hpp).
#include <cuda_runtime.h>

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

#include "../../core/device_part.hpp"
#include "host_copy.cuh"
#include "launch.cuh"
#include "horizon/cuda.hpp"

namespace horizon::detail {
namespace {

__global__ void to_global_ids(point_id* ids, std::int64_t count, const point_id* global) {
  const std::int64_t stride = static_cast<std::int64_t>(gridDim.x) * blockDim.x;
  for (std::int64_t e = static_cast<std::int64_t>(blockIdx.x) * blockDim.x + threadIdx.x; e < count; e += stride)
    ids[e] = global[ids[e]];
}

constexpr std::int64_t ids_per_buffer = static_cast<std::int64_t>(staging_bytes / sizeof(point_id));

/// Rows [first, last) of a part's list: one staging buffer's worth, or a single longer row.
struct Chunk {
  std::size_t first, last;
};

class DevicePartOnGpu final : public DevicePart {
public:
  DevicePartOnGpu(PointView local, std::span<const point_id> global, const SearchOptions& options)
      : device_(options.device), lease_(options.device) {
    const cudaStream_t stream = lease_.get();
    MemoryMeter meter(device_, stream, options.gpu_max_memory);
    {
      DeviceArray<double> xyz(local.size() * static_cast<std::size_t>(local.dims()), meter);
      upload_coordinates(xyz.get(), local, stream);
      list_ = search_device(xyz.get(), local.size(), local.dims(), options, stream);
    }
    if (list_.total() > 0) {
      DeviceArray<point_id> map(global.size(), meter);
      HORIZON_CUDA_CHECK(cudaMemcpyAsync(map.get(), global.data(), global.size() * sizeof(point_id),
                                         cudaMemcpyHostToDevice, stream));
      // The list is this object's own: its ids are rewritten in place.
      auto* ids = const_cast<point_id*>(list_.indices());
      to_global_ids<<<std::min(blocks_for(static_cast<std::size_t>(list_.total())), 8192u), block_size, 0, stream>>>(
          ids, list_.total(), map.get());
      check_launch("to_global_ids");
    }
    offsets_.resize(local.size() + 1);
    copy_to_host(offsets_.data(), list_.offsets(), offsets_.size() * sizeof(std::int64_t), stream);
    for (std::size_t first = 0, rows = local.size(); first < rows;) {
      const auto end = std::upper_bound(offsets_.begin() + first + 1, offsets_.end(), offsets_[first] + ids_per_buffer);
      const std::size_t last = std::max(static_cast<std::size_t>(end - offsets_.begin()) - 1, first + 1);
      chunks_.push_back({first, last});
      first = last;
    }
  }

  const Buffer<std::int64_t>& offsets() const override { return offsets_; }
  const std::vector<Chunk>& chunks() const { return chunks_; }
  std::int64_t entries(const Chunk& c) const { return offsets_[c.last] - offsets_[c.first]; }

  /// Starts chunk c's copy into staging buffer c % 2 (a row longer than a buffer: nothing).
  void issue(std::size_t c, Staging& staging) const {
    select_device(device_);
    const Chunk& chunk = chunks_[c];
    if (entries(chunk) > ids_per_buffer) return;
    if (entries(chunk) > 0)
      HORIZON_CUDA_CHECK(cudaMemcpyAsync(staging.buffer(c % 2), list_.indices() + offsets_[chunk.first],
                                         static_cast<std::size_t>(entries(chunk)) * sizeof(point_id),
                                         cudaMemcpyDeviceToHost, lease_.get()));
    HORIZON_CUDA_CHECK(cudaEventRecord(staging.done(c % 2), lease_.get()));
  }

  /// Chunk c's ids once they are on the host: in its staging buffer, or (a single long row)
  /// copied straight to `row_at` (nullptr: not wanted).
  const point_id* arrived(std::size_t c, Staging& staging, point_id* row_at) const {
    select_device(device_);
    const Chunk& chunk = chunks_[c];
    if (entries(chunk) > ids_per_buffer) {
      if (row_at)
        HORIZON_CUDA_CHECK(cudaMemcpyAsync(row_at, list_.indices() + offsets_[chunk.first],
                                           static_cast<std::size_t>(entries(chunk)) * sizeof(point_id),
                                           cudaMemcpyDeviceToHost, lease_.get()));
      HORIZON_CUDA_CHECK(cudaStreamSynchronize(lease_.get()));
      return nullptr;
    }
    HORIZON_CUDA_CHECK(cudaEventSynchronize(staging.done(c % 2)));
    return reinterpret_cast<const point_id*>(staging.buffer(c % 2));
  }

private:
  int device_;
  StreamLease lease_;  // outlives list_, which is freed on its stream
  DeviceNeighborList list_;
  Buffer<std::int64_t> offsets_;
  std::vector<Chunk> chunks_;
};

}  // namespace

std::unique_ptr<DevicePart> search_on_device(PointView local, std::span<const point_id> global,
                                             const SearchOptions& options) {
  select_device(options.device);
  return std::make_unique<DevicePartOnGpu>(local, global, options);
}

// Each part's chunks come back through its own pair of staging buffers, the next chunk of every
// part under way while all cores place the rows of the chunks that have arrived: no thread per
// part, whose OpenMP teams would share the cores.
void copy_part_rows(const std::vector<PartRows>& parts, const std::int64_t* at, point_id* indices) {
  auto part_of = [&](std::size_t p) -> const DevicePartOnGpu& { return *static_cast<const DevicePartOnGpu*>(parts[p].part); };
  std::vector<std::unique_ptr<StagingLease>> staging;
  std::size_t most = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    staging.push_back(std::make_unique<StagingLease>());
    most = std::max(most, part_of(p).chunks().size());
    if (!part_of(p).chunks().empty()) part_of(p).issue(0, **staging[p]);
  }
  for (std::size_t c = 0; c < most; ++c) {
    for (std::size_t p = 0; p < parts.size(); ++p)
      if (c + 1 < part_of(p).chunks().size()) part_of(p).issue(c + 1, **staging[p]);
    for (std::size_t p = 0; p < parts.size(); ++p) {
      if (c >= part_of(p).chunks().size()) continue;
      const Chunk chunk = part_of(p).chunks()[c];
      point_id* row_at = parts[p].keep[chunk.first] ? indices + at[parts[p].global[chunk.first]] : nullptr;
      if (const point_id* staged = part_of(p).arrived(c, **staging[p], row_at))
        place_rows(parts[p], part_of(p).offsets().data(), chunk.first, chunk.last, staged, at, indices);
    }
  }
}

}  // namespace horizon::detail
