// The CUDA backend (thesis ch. 5, done the modern way): a binning step that sorts points by
// cell with CUB radix sort and builds a cell start table, then the build step in two passes,
// count -> exclusive scan -> fill, so no row has a fixed maximum and offsets are 64-bit.
// Rows are sorted on chip (row_sort.cuh, or fused with the fill for rows of 65-256; CUB's
// segmented sort for rows over 2048). The pair test is metric_accumulate(),
// compiled with -fmad=false, so every decision matches the CPU backends bit for bit.
#include <cub/cub.cuh>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <vector>

#include "../../core/parallel_copy.hpp"
#include "../backends.hpp"
#include "device_index.cuh"
#include "device_memory.hpp"
#include "launch.cuh"
#include "row_sort.cuh"
#include "horizon/cuda.hpp"
#include "horizon/grid.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon {
namespace detail {
namespace {

// ---- Build ---------------------------------------------------------------------------------

/// One thread per point in sorted order, so a warp's points share most of their candidates.
/// Counting writes counts[id] = |family|; filling writes the family of each point whose id is
/// in [first_id, last_id) at out[offsets[id] - base].
template <Metric M, int D, bool Half, bool Fill>
__global__ void families(DeviceIndexView ix, double threshold, std::int64_t* counts,
                         const std::int64_t* offsets, point_id* out, point_id first_id,
                         point_id last_id, std::int64_t base) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= ix.n) return;
  const point_id self = ix.order[p];
  if (self >= ix.queries) {
    if (!Fill) counts[self] = 0;
    return;
  }
  if (Fill && (self < first_id || self >= last_id)) return;
  const double xi = ix.x[p], yi = ix.y[p], zi = ix.z[p];
  const std::int64_t cx = ix.grid.cell_of(xi, 0), cy = ix.grid.cell_of(yi, 1);
  const std::int64_t cz = D == 3 ? ix.grid.cell_of(zi, 2) : 0;
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  point_id* row = Fill ? out + (offsets[self] - base) : nullptr;
  std::int64_t found = 0;
  for (int dz = -reach_z; dz <= reach_z; ++dz)
    for (int dy = -k; dy <= k; ++dy) {
      std::int64_t begin, end;
      ix.row(cx, cy + dy, cz + dz, begin, end);
      for (std::int64_t q = begin; q < end; ++q) {
        const double d = metric_accumulate<M>(xi - ix.x[q], yi - ix.y[q], D == 3 ? zi - ix.z[q] : 0.0);
        const point_id other = ix.order[q];
        const bool keep = Half ? other > self : q != p;
        if (d < threshold && keep) {
          if (Fill) row[found] = other;
          ++found;
        }
      }
    }
  if (!Fill) counts[self] = found;
}

template <bool Fill, Metric M, int D>
void launch_half(const DeviceIndexView& ix, const SearchOptions& o, std::int64_t* counts,
                 const std::int64_t* offsets, point_id* out, point_id first, point_id last,
                 std::int64_t base, cudaStream_t stream) {
  const double threshold = metric_threshold(M, o.horizon);
  const unsigned blocks = blocks_for(static_cast<std::size_t>(ix.n));
  if (o.half)
    families<M, D, true, Fill><<<blocks, block_size, 0, stream>>>(ix, threshold, counts, offsets, out, first, last, base);
  else
    families<M, D, false, Fill><<<blocks, block_size, 0, stream>>>(ix, threshold, counts, offsets, out, first, last, base);
  check_launch(Fill ? "families<fill>" : "families<count>");
}

template <bool Fill, Metric M>
void launch_dims(const DeviceIndexView& ix, const SearchOptions& o, std::int64_t* counts,
                 const std::int64_t* offsets, point_id* out, point_id first, point_id last,
                 std::int64_t base, cudaStream_t stream) {
  if (ix.grid.dims == 3)
    launch_half<Fill, M, 3>(ix, o, counts, offsets, out, first, last, base, stream);
  else
    launch_half<Fill, M, 2>(ix, o, counts, offsets, out, first, last, base, stream);
}

template <bool Fill>
void launch_families(const DeviceIndexView& ix, const SearchOptions& o, std::int64_t* counts,
                     const std::int64_t* offsets, point_id* out, point_id first, point_id last,
                     std::int64_t base, cudaStream_t stream) {
  switch (o.metric) {
    case Metric::euclidean: return launch_dims<Fill, Metric::euclidean>(ix, o, counts, offsets, out, first, last, base, stream);
    case Metric::manhattan: return launch_dims<Fill, Metric::manhattan>(ix, o, counts, offsets, out, first, last, base, stream);
    case Metric::chebyshev: return launch_dims<Fill, Metric::chebyshev>(ix, o, counts, offsets, out, first, last, base, stream);
  }
}

/// Row offsets by id: count each family, then an inclusive scan into offsets[1..n].
DeviceArray<std::int64_t> count_offsets(const DeviceIndex& index, const SearchOptions& options,
                                        std::size_t count, cudaStream_t stream, MemoryMeter& meter,
                                        std::int64_t& total, std::int64_t& longest) {
  DeviceArray<std::int64_t> counts(count, meter), offsets(count + 1, meter);
  launch_families<false>(index.view(options.queries), options, counts.get(), nullptr, nullptr, 0, 0, 0, stream);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, temp_bytes, counts.get(), offsets.get() + 1,
                                                   static_cast<std::int64_t>(count), stream));
  DeviceArray<char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp.get(), temp_bytes, counts.get(), offsets.get() + 1,
                                                   static_cast<std::int64_t>(count), stream));
  DeviceArray<std::int64_t> most(1, meter);
  std::size_t max_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceReduce::Max(nullptr, max_bytes, counts.get(), most.get(), static_cast<std::int64_t>(count), stream));
  DeviceArray<char> max_temp(max_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceReduce::Max(max_temp.get(), max_bytes, counts.get(), most.get(), static_cast<std::int64_t>(count), stream));
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&total, offsets.get() + count, sizeof(total), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&longest, most.get(), sizeof(longest), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  return offsets;
}

struct MinusBase {
  std::int64_t base;
  __host__ __device__ std::int64_t operator()(std::int64_t offset) const { return offset - base; }
};

/// Bytes of scratch the segmented sort of `entries` entries in `rows` rows needs.
std::size_t sort_scratch_bytes(std::int64_t entries, std::int64_t rows, const std::int64_t* offsets) {
  std::size_t bytes = 0;
  const auto begins = thrust::make_transform_iterator(offsets, MinusBase{0});
  cub::DoubleBuffer<point_id> keys(nullptr, nullptr);
  HORIZON_CUDA_CHECK(cub::DeviceSegmentedSort::SortKeys(nullptr, bytes, keys, entries, rows, begins, begins + 1));
  return bytes;
}

constexpr int fused_min = 64;  // longer rows take the fused kernel

// ---- Fused fill and sort for rows of 65 to 256 ------------------------------------------------
// A warp per point: lanes test 32 consecutive candidates at once (coalesced loads), ballot the
// hits into a row staged in shared memory, sort it in registers (cub::WarpMergeSort) and store it
// with coalesced writes. Nsight Compute on the two-kernel path (n = 200, m = 3.015, H100): the
// thread-per-point fill spent 21.5 ms on uncoalesced row stores, the warp sort 10.8 ms on
// blocked loads.

template <Metric M, int D, bool Half, int Items>
__global__ void __launch_bounds__(block_size) fill_sorted_rows(DeviceIndexView ix, double threshold,
                                                               const std::int64_t* offsets, point_id* out,
                                                               point_id first_id, point_id last_id,
                                                               std::int64_t base) {
  constexpr int warps = block_size / 32, capacity = 32 * Items;
  using WarpSort = cub::WarpMergeSort<point_id, Items, 32>;
  __shared__ typename WarpSort::TempStorage temp[warps];
  __shared__ point_id staged[warps][capacity];
  const int warp = threadIdx.x / 32, lane = threadIdx.x % 32;
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(warps) + warp;
  if (p >= ix.n) return;
  const point_id self = ix.order[p];
  if (self >= ix.queries || self < first_id || self >= last_id) return;  // uniform across the warp
  const double xi = ix.x[p], yi = ix.y[p], zi = ix.z[p];
  const std::int64_t cx = ix.grid.cell_of(xi, 0), cy = ix.grid.cell_of(yi, 1);
  const std::int64_t cz = D == 3 ? ix.grid.cell_of(zi, 2) : 0;
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  point_id* row = staged[warp];
  int found = 0;
  for (int dz = -reach_z; dz <= reach_z; ++dz)
    for (int dy = -k; dy <= k; ++dy) {
      std::int64_t begin, end;
      ix.row(cx, cy + dy, cz + dz, begin, end);
      for (std::int64_t q0 = begin; q0 < end; q0 += 32) {
        const std::int64_t q = q0 + lane;
        bool hit = false;
        point_id other = 0;
        if (q < end) {
          const double d = metric_accumulate<M>(xi - ix.x[q], yi - ix.y[q], D == 3 ? zi - ix.z[q] : 0.0);
          other = ix.order[q];
          hit = d < threshold && (Half ? other > self : q != p);
        }
        const unsigned ballot = __ballot_sync(0xffffffffu, hit);
        if (hit) row[found + __popc(ballot & ((1u << lane) - 1))] = other;
        found += __popc(ballot);
      }
    }
  __syncwarp();
  point_id keys[Items];
  for (int i = 0; i < Items; ++i) {
    const int at = lane * Items + i;
    keys[i] = at < found ? row[at] : INT_MAX;
  }
  WarpSort(temp[warp]).Sort(keys, IdLess());
  __syncwarp();
  for (int i = 0; i < Items; ++i) row[lane * Items + i] = keys[i];
  __syncwarp();
  point_id* destination = out + (offsets[self] - base);
  for (int at = lane; at < found; at += 32) destination[at] = row[at];
}

template <Metric M, int D, bool Half>
void launch_fused(const DeviceIndexView& ix, double threshold, const std::int64_t* offsets, point_id* out,
                  point_id first, point_id last, std::int64_t base, std::int64_t longest, cudaStream_t stream) {
  const unsigned blocks = blocks_for(static_cast<std::size_t>(ix.n) * 32);
  if (longest <= 128)
    fill_sorted_rows<M, D, Half, 4><<<blocks, block_size, 0, stream>>>(ix, threshold, offsets, out, first, last, base);
  else
    fill_sorted_rows<M, D, Half, 8><<<blocks, block_size, 0, stream>>>(ix, threshold, offsets, out, first, last, base);
  check_launch("fill_sorted_rows");
}

template <Metric M>
void launch_fused_metric(const DeviceIndexView& ix, const SearchOptions& o, const std::int64_t* offsets,
                         point_id* out, point_id first, point_id last, std::int64_t base, std::int64_t longest,
                         cudaStream_t stream) {
  const double threshold = metric_threshold(M, o.horizon);
  if (ix.grid.dims == 3) {
    if (o.half) launch_fused<M, 3, true>(ix, threshold, offsets, out, first, last, base, longest, stream);
    else launch_fused<M, 3, false>(ix, threshold, offsets, out, first, last, base, longest, stream);
  } else {
    if (o.half) launch_fused<M, 2, true>(ix, threshold, offsets, out, first, last, base, longest, stream);
    else launch_fused<M, 2, false>(ix, threshold, offsets, out, first, last, base, longest, stream);
  }
}

void fill_sorted(const DeviceIndexView& ix, const SearchOptions& o, const std::int64_t* offsets, point_id* out,
                 point_id first, point_id last, std::int64_t base, std::int64_t longest, cudaStream_t stream) {
  switch (o.metric) {
    case Metric::euclidean: return launch_fused_metric<Metric::euclidean>(ix, o, offsets, out, first, last, base, longest, stream);
    case Metric::manhattan: return launch_fused_metric<Metric::manhattan>(ix, o, offsets, out, first, last, base, longest, stream);
    case Metric::chebyshev: return launch_fused_metric<Metric::chebyshev>(ix, o, offsets, out, first, last, base, longest, stream);
  }
}

/// Fills and sorts the rows of ids [first, last): their entries go to rows_out, which holds
/// offsets[last] - offsets[first] entries; `spare` is as large when a row is longer than
/// sortable on chip (the segmented sort's second buffer). Returns the buffer holding the result.
point_id* fill_rows(const DeviceIndex& index, const SearchOptions& options, const std::int64_t* offsets,
                    std::int64_t base, std::int64_t entries, std::int64_t longest, point_id first,
                    point_id last, point_id* rows_out, point_id* spare, cudaStream_t stream,
                    MemoryMeter& meter) {
  // Rows of up to 64 are cheaper with a thread per point (measured, lattice n = 400, m = 1.5:
  // 0.074 s that way, 0.166 s with a warp per point); longer ones with the fused kernel
  // (m = 3.015: 0.341 -> 0.302 s).
  if (options.sort_rows && longest > fused_min && longest <= warp_row) {
    if (entries > 0) fill_sorted(index.view(options.queries), options, offsets, rows_out, first, last, base, longest, stream);
    return rows_out;
  }
  launch_families<true>(index.view(options.queries), options, nullptr, offsets, rows_out, first, last, base, stream);
  if (!options.sort_rows || entries == 0) return rows_out;
  const std::int64_t rows = last - first;
  if (longest <= block_row) {
    sort_rows_on_chip(rows_out, offsets + first, base, rows, longest, stream);
    return rows_out;
  }
  const auto begins = thrust::make_transform_iterator(offsets + first, MinusBase{base});
  cub::DoubleBuffer<point_id> keys(rows_out, spare);
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceSegmentedSort::SortKeys(nullptr, temp_bytes, keys, entries, rows,
                                                        begins, begins + 1, stream));
  DeviceArray<char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceSegmentedSort::SortKeys(temp.get(), temp_bytes, keys, entries, rows,
                                                        begins, begins + 1, stream));
  return keys.Current();
}

/// Whether the rows need the segmented sort and its second buffer.
bool needs_spare(const SearchOptions& options, std::int64_t longest) {
  return options.sort_rows && longest > block_row;
}

std::size_t free_device_bytes() {
  std::size_t free = 0, total = 0;
  HORIZON_CUDA_CHECK(cudaMemGetInfo(&free, &total));
  return free;
}

void select_device(int device) {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess || device >= count)
    throw Error("CUDA device " + std::to_string(device) + " does not exist (" +
                std::to_string(count) + " visible)");
  HORIZON_CUDA_CHECK(cudaSetDevice(device));
}

/// Device-to-host copy through two pinned staging buffers: the GPU fills one while all cores
/// empty the other, so a pageable destination still sees close to pinned bandwidth.
void copy_to_host(void* host, const void* device, std::size_t bytes, cudaStream_t stream) {
  constexpr std::size_t chunk = std::size_t{64} << 20;
  if (bytes <= chunk) {
    HORIZON_CUDA_CHECK(cudaMemcpyAsync(host, device, bytes, cudaMemcpyDeviceToHost, stream));
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    return;
  }
  void* staging[2];
  cudaEvent_t copied[2];
  HORIZON_CUDA_CHECK(cudaMallocHost(&staging[0], 2 * chunk));
  staging[1] = static_cast<char*>(staging[0]) + chunk;
  for (auto& e : copied) HORIZON_CUDA_CHECK(cudaEventCreateWithFlags(&e, cudaEventDisableTiming));
  const std::size_t chunks = (bytes + chunk - 1) / chunk;
  auto issue = [&](std::size_t c) {
    const std::size_t at = c * chunk, size = std::min(chunk, bytes - at);
    HORIZON_CUDA_CHECK(cudaMemcpyAsync(staging[c % 2], static_cast<const char*>(device) + at, size,
                                       cudaMemcpyDeviceToHost, stream));
    HORIZON_CUDA_CHECK(cudaEventRecord(copied[c % 2], stream));
  };
  issue(0);
  for (std::size_t c = 0; c < chunks; ++c) {
    if (c + 1 < chunks) issue(c + 1);
    HORIZON_CUDA_CHECK(cudaEventSynchronize(copied[c % 2]));
    const std::size_t at = c * chunk, size = std::min(chunk, bytes - at);
    parallel_copy(static_cast<char*>(host) + at, staging[c % 2], size);
  }
  for (auto& e : copied) cudaEventDestroy(e);
  cudaFreeHost(staging[0]);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

bool cuda_usable() {
  int count = 0;
  return cudaGetDeviceCount(&count) == cudaSuccess && count > 0;
}

// Host arrays in, host CSR out. When the list does not fit on the GPU it is built in batches
// of rows, each filled, sorted and copied back before the next.
NeighborList search_cuda(PointView points, const SearchOptions& options, SearchStats& stats) {
  select_device(options.device);
  stats.gpu_name = cuda_device_name(options.device);
  stats.threads = 1;
  const std::size_t n = points.size();
  const int dims = points.dims();
  MemoryMeter meter;
  cudaStream_t stream;
  HORIZON_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  struct StreamGuard {
    cudaStream_t s;
    ~StreamGuard() { cudaStreamDestroy(s); }
  } guard{stream};

  auto clock = std::chrono::steady_clock::now();
  std::vector<double> promoted;
  if (points.is_float32()) {
    promoted.resize(n * static_cast<std::size_t>(dims));
    for (std::size_t i = 0; i < n; ++i)
      for (int a = 0; a < dims; ++a) promoted[i * dims + a] = points(i, a);
  }
  const double* host_xyz = points.is_float32() ? promoted.data() : points.float64_data();
  DeviceArray<double> xyz(n * static_cast<std::size_t>(dims), meter);
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(xyz.get(), host_xyz, xyz.bytes(), cudaMemcpyHostToDevice, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  stats.host_to_device_seconds = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  const DeviceIndex index(xyz.get(), n, dims, options, stream, meter);
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  stats.grid_seconds = seconds_since(clock);
  xyz.reset();

  auto kernels = std::chrono::steady_clock::now();
  std::int64_t total = 0, longest = 0;
  DeviceArray<std::int64_t> offsets = count_offsets(index, options, n, stream, meter, total, longest);
  Buffer<std::int64_t> host_offsets(n + 1);
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(host_offsets.data(), offsets.get(), offsets.bytes(), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  Buffer<point_id> indices(static_cast<std::size_t>(total));

  // Batches of rows sized to what is free: the list (twice when rows need the segmented sort).
  const std::size_t free = free_device_bytes();
  const std::size_t usable = free > (std::size_t{256} << 20) ? free - (std::size_t{256} << 20) : free / 2;
  const std::int64_t fits = std::max<std::int64_t>(1, static_cast<std::int64_t>(usable / (3 * sizeof(point_id))));
  const std::int64_t batch_entries = options.gpu_batch_entries > 0 ? std::min(fits, options.gpu_batch_entries) : fits;
  double copy_seconds = 0;
  for (std::size_t first = 0; first < n;) {
    std::size_t last = first;
    // Rows up to the batch's size (a single larger row still goes alone).
    const std::int64_t limit = host_offsets[first] + batch_entries;
    last = static_cast<std::size_t>(std::upper_bound(host_offsets.begin() + first + 1, host_offsets.end(), limit) -
                                    host_offsets.begin()) - 1;
    last = std::max(last, first + 1);
    const std::int64_t base = host_offsets[first], entries = host_offsets[last] - base;
    DeviceArray<point_id> rows(static_cast<std::size_t>(entries), meter);
    DeviceArray<point_id> spare(needs_spare(options, longest) ? static_cast<std::size_t>(entries) : 0, meter);
    const point_id* result = fill_rows(index, options, offsets.get(), base, entries, longest, static_cast<point_id>(first),
                                       static_cast<point_id>(last), rows.get(), spare.get(), stream, meter);
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    const auto copy_start = std::chrono::steady_clock::now();
    copy_to_host(indices.data() + base, result, static_cast<std::size_t>(entries) * sizeof(point_id), stream);
    copy_seconds += seconds_since(copy_start);
    first = last;
  }
  stats.device_to_host_seconds = copy_seconds;
  stats.kernel_seconds = seconds_since(kernels) - copy_seconds;
  stats.search_seconds = stats.kernel_seconds + copy_seconds;
  stats.peak_gpu_bytes = meter.peak;
  return NeighborList(std::move(host_offsets), std::move(indices), options.half);
}

}  // namespace detail

void DeviceNeighborList::Free::operator()(void* pointer) const { cudaFree(pointer); }

NeighborList DeviceNeighborList::to_host(bool half) const {
  Buffer<std::int64_t> offsets(points_ + 1, 0);
  Buffer<point_id> indices(static_cast<std::size_t>(total_));
  if (offsets_) detail::copy_to_host(offsets.data(), offsets_.get(), offsets.size() * sizeof(std::int64_t), nullptr);
  if (total_) detail::copy_to_host(indices.data(), indices_.get(), indices.size() * sizeof(point_id), nullptr);
  return NeighborList(std::move(offsets), std::move(indices), half);
}

DeviceNeighborList search_device(const double* xyz, std::size_t count, int dims,
                                 const SearchOptions& options, cuda_stream stream, SearchStats* stats) {
  validate_horizon(options.horizon, options.cells_per_horizon);
  if (dims != 2 && dims != 3) throw Error("points must have 2 or 3 coordinates, not " + std::to_string(dims));
  DeviceNeighborList list;
  list.points_ = count;
  detail::MemoryMeter meter;
  detail::DeviceArray<std::int64_t> offsets(count + 1, meter);
  if (count == 0) {
    HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
    list.offsets_.reset(offsets.release());
    return list;
  }
  auto start = std::chrono::steady_clock::now();
  const detail::DeviceIndex index(xyz, count, dims, options, stream, meter);
  if (stats) {
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    stats->grid_seconds = detail::seconds_since(start);
    start = std::chrono::steady_clock::now();
  }
  std::int64_t longest = 0;
  offsets = detail::count_offsets(index, options, count, stream, meter, list.total_, longest);

  const bool spare_needed = detail::needs_spare(options, longest);
  const std::size_t list_bytes = static_cast<std::size_t>(list.total_) * sizeof(point_id);
  const std::size_t needed = (spare_needed ? 2 : 1) * list_bytes +
                             (spare_needed ? detail::sort_scratch_bytes(list.total_, static_cast<std::int64_t>(count), offsets.get()) : 0);
  const std::size_t free = detail::free_device_bytes();
  if (needed > free)
    throw DeviceOutOfMemory("the neighbour list needs " + std::to_string(needed) + " bytes of GPU memory, " +
                                std::to_string(free) + " are free (the host API builds it in batches)",
                            needed, free);
  detail::DeviceArray<point_id> rows(static_cast<std::size_t>(list.total_), meter);
  detail::DeviceArray<point_id> spare(spare_needed ? static_cast<std::size_t>(list.total_) : 0, meter);
  point_id* result = detail::fill_rows(index, options, offsets.get(), 0, list.total_, longest, 0,
                                       static_cast<point_id>(count), rows.get(), spare.get(), stream, meter);
  list.indices_.reset(result == rows.get() ? rows.release() : spare.release());
  list.offsets_.reset(offsets.release());
  if (stats) {
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    stats->backend = Backend::cuda;
    stats->search_seconds = detail::seconds_since(start);
    stats->kernel_seconds = stats->grid_seconds + stats->search_seconds;
    stats->peak_gpu_bytes = meter.peak;
  }
  return list;
}

std::string cuda_device_name(int device) {
  cudaDeviceProp properties;
  if (cudaGetDeviceProperties(&properties, device) != cudaSuccess) return "";
  return properties.name;
}

}  // namespace horizon
