#pragma once
// Included at the end of search.cu only (it uses the host path's stream pool, upload and
// staging): a part of a multi-GPU search whose rows stay on its GPU (core/device_part.hpp).
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <span>
#include <vector>

#include "../../core/device_part.hpp"
#include "host_copy.cuh"
#include "launch.cuh"
#include "horizon/cuda.hpp"

namespace horizon::detail {

namespace {

/// own[rows[k]] = 1: the points of a part that get rows.
__global__ void mark_own(const point_id* rows, std::int64_t count, std::uint8_t* own) {
  const std::int64_t k = static_cast<std::int64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < count) own[rows[k]] = 1;
}

/// The owned rows' offsets in a local list whose other rows are empty, and their global ids:
/// offsets[k] = local[rows[k]] (row k ends where row k + 1 starts), ids[k] = global[rows[k]].
__global__ void owned_rows_of(const std::int64_t* local, const point_id* rows, std::int64_t count,
                              const point_id* global, std::int64_t* offsets, point_id* ids) {
  const std::int64_t k = static_cast<std::int64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < count) {
    offsets[k] = local[rows[k]];
    ids[k] = global[rows[k]];
  }
}

constexpr std::int64_t ids_per_buffer = static_cast<std::int64_t>(staging_bytes / sizeof(point_id));

/// Rows [first, last) of a part: one staging buffer's worth, or a single longer row.
struct Chunk {
  std::size_t first, last;
};

std::vector<Chunk> chunks_of(std::span<const std::int64_t> offsets) {
  std::vector<Chunk> chunks;
  for (std::size_t first = 0, rows = offsets.size() - 1; first < rows;) {
    const auto end = std::upper_bound(offsets.begin() + first + 1, offsets.end(), offsets[first] + ids_per_buffer);
    const std::size_t last = std::max(static_cast<std::size_t>(end - offsets.begin()) - 1, first + 1);
    chunks.push_back({first, last});
    first = last;
  }
  return chunks;
}

/// A part's rows coming back to the host chunk by chunk, through a pair of staging buffers.
class PartCopy {
public:
  explicit PartCopy(const PartRows& rows) : rows_(rows), chunks_(chunks_of(rows.offsets)) {}
  const std::vector<Chunk>& chunks() const { return chunks_; }

  /// Starts chunk c's copy into staging buffer c % 2 (a row longer than a buffer: nothing).
  void issue(std::size_t c) {
    select_device(rows_.part->device);
    if (entries(c) > ids_per_buffer) return;
    if (entries(c) > 0)
      HORIZON_CUDA_CHECK(cudaMemcpyAsync(staging_->buffer(c % 2), source(c), bytes(c), cudaMemcpyDeviceToHost, stream()));
    HORIZON_CUDA_CHECK(cudaEventRecord(staging_->done(c % 2), stream()));
  }

  /// Chunk c's ids once they are on the host: in its staging buffer, or (a single long row)
  /// copied straight to its place (nullptr then).
  const point_id* arrived(std::size_t c, const std::int64_t* at, point_id* indices) {
    select_device(rows_.part->device);
    if (entries(c) > ids_per_buffer) {
      HORIZON_CUDA_CHECK(cudaMemcpyAsync(indices + at[rows_.ids[chunks_[c].first]], source(c), bytes(c),
                                         cudaMemcpyDeviceToHost, stream()));
      HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream()));
      return nullptr;
    }
    HORIZON_CUDA_CHECK(cudaEventSynchronize(staging_->done(c % 2)));
    return reinterpret_cast<const point_id*>(staging_->buffer(c % 2));
  }

private:
  std::int64_t entries(std::size_t c) const { return rows_.offsets[chunks_[c].last] - rows_.offsets[chunks_[c].first]; }
  std::size_t bytes(std::size_t c) const { return static_cast<std::size_t>(entries(c)) * sizeof(point_id); }
  const point_id* source(std::size_t c) const { return rows_.part->rows.indices() + rows_.offsets[chunks_[c].first]; }
  cudaStream_t stream() const { return reinterpret_cast<cudaStream_t>(rows_.part->rows.stream()); }
  PartRows rows_;
  std::vector<Chunk> chunks_;
  StagingLease staging_;
};

}  // namespace

DevicePart search_local_part(const LocalPart& part, const SearchOptions& given, SearchStats* stats) {
  SearchOptions options = given;
  options.devices.clear();
  options.queries = 0;
  if (options.device >= max_devices) throw Error("CUDA device " + std::to_string(options.device) + " is past the 64 supported");
  select_device(options.device);
  // The stream goes back to the pool at the end, but pooled streams live as long as the
  // process: the part's arrays are freed on it whenever the part is destroyed.
  const StreamLease lease(options.device);
  const cudaStream_t stream = lease.get();
  MemoryMeter meter(options.device, stream, options.gpu_max_memory);
  const std::size_t n = part.points.size(), owned = part.owned_rows.size();
  DevicePart result;
  result.device = options.device;
  result.halo = n - owned;

  // Its points, their global ids and which are its own; then the search, which names every
  // point by its global id as it stores it and gives the halo empty rows: the list's entries
  // are the part's rows as they stand, and only their offsets are picked out.
  auto clock = std::chrono::steady_clock::now();
  DeviceArray<point_id> global(n, meter), rows(owned, meter);
  DeviceArray<std::uint8_t> own(n, meter);
  DeviceNeighborList local;
  {
    DeviceArray<double> xyz(n * static_cast<std::size_t>(part.points.dims()), meter);
    if (n > 0) upload_coordinates(xyz.get(), part.points, stream);
    HORIZON_CUDA_CHECK(cudaMemcpyAsync(global.get(), part.global.data(), global.bytes(), cudaMemcpyHostToDevice, stream));
    HORIZON_CUDA_CHECK(cudaMemcpyAsync(rows.get(), part.owned_rows.data(), rows.bytes(), cudaMemcpyHostToDevice, stream));
    HORIZON_CUDA_CHECK(cudaMemsetAsync(own.get(), 0, own.bytes(), stream));
    if (owned > 0) {
      mark_own<<<blocks_for(owned), block_size, 0, stream>>>(rows.get(), static_cast<std::int64_t>(owned), own.get());
      check_launch("mark_own");
    }
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    if (stats) stats->host_to_device_seconds = seconds_since(clock);
    clock = std::chrono::steady_clock::now();
    const point_id bound = n > 0 ? part.global.back() + 1 : 0;
    const PartNaming naming{global.get(), bound, own.get()};
    local = DeviceListAccess::search(xyz.get(), n, part.points.dims(), options, stream, nullptr, &naming);
  }
  DeviceArray<std::int64_t> offsets(owned + 1, meter);
  DeviceArray<point_id> ids(owned, meter);
  const std::int64_t total = local.total();
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(offsets.get() + owned, &total, sizeof(total), cudaMemcpyHostToDevice, stream));
  if (owned > 0) {
    owned_rows_of<<<blocks_for(owned), block_size, 0, stream>>>(local.offsets(), rows.get(),
                                                                static_cast<std::int64_t>(owned), global.get(),
                                                                offsets.get(), ids.get());
    check_launch("owned_rows_of");
  }
  DeviceListAccess::set(result.rows, offsets.release(), DeviceListAccess::release_indices(local), owned, total,
                        stream);
  result.device_ids = {ids.release(), DeviceNeighborList::Free{stream}};
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));  // before `total` and `local` go
  if (stats) {
    stats->backend = Backend::cuda;
    stats->kernel_seconds = stats->search_seconds = seconds_since(clock);
    stats->peak_gpu_bytes = meter.peak;
  }
  return result;
}

Buffer<std::int64_t> host_offsets(const DevicePart& part) {
  select_device(part.device);
  Buffer<std::int64_t> offsets(part.rows.size() + 1);
  copy_to_host(offsets.data(), part.rows.offsets(), offsets.size() * sizeof(std::int64_t),
               reinterpret_cast<cudaStream_t>(part.rows.stream()));
  return offsets;
}

// Each part's chunks come back through its own pair of staging buffers, the next chunk of every
// part under way while all cores place the rows of the chunks that have arrived: no thread per
// part, whose OpenMP teams would share the cores.
void copy_part_rows(const std::vector<PartRows>& parts, const std::int64_t* at, point_id* indices) {
  std::vector<std::unique_ptr<PartCopy>> copies;
  std::size_t most = 0;
  for (const PartRows& rows : parts) {
    copies.push_back(std::make_unique<PartCopy>(rows));
    most = std::max(most, copies.back()->chunks().size());
    if (!copies.back()->chunks().empty()) copies.back()->issue(0);
  }
  for (std::size_t c = 0; c < most; ++c) {
    for (auto& copy : copies)
      if (c + 1 < copy->chunks().size()) copy->issue(c + 1);
    for (std::size_t p = 0; p < parts.size(); ++p) {
      if (c >= copies[p]->chunks().size()) continue;
      const Chunk chunk = copies[p]->chunks()[c];
      if (const point_id* staged = copies[p]->arrived(c, at, indices))
        place_rows(parts[p], chunk.first, chunk.last, staged, at, indices);
    }
  }
}

}  // namespace horizon::detail
