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
#include <cstdlib>
#include <cstring>
#include <type_traits>
#include <vector>

#include "../backends.hpp"
#include "device_index.cuh"
#include "cell_kernel.cuh"
#include "device_memory.hpp"
#include "host_copy.cuh"
#include "launch.cuh"
#include "row_sort.cuh"
#include "horizon/cuda.hpp"
#include "horizon/grid.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon {
namespace detail {
namespace {

// ---- Build ----------------------------------------------------------------------------------

/// Calls f(metric, dims, half), each as a compile-time constant.
template <typename F>
void with_shape(Metric metric, int dims, bool half, F&& f) {
  const auto with_dims = [&](auto m) {
    const auto with_half = [&](auto d) {
      if (half) f(m, d, std::true_type{});
      else f(m, d, std::false_type{});
    };
    if (dims == 3) with_half(std::integral_constant<int, 3>{});
    else with_half(std::integral_constant<int, 2>{});
  };
  switch (metric) {
    case Metric::euclidean: return with_dims(std::integral_constant<Metric, Metric::euclidean>{});
    case Metric::manhattan: return with_dims(std::integral_constant<Metric, Metric::manhattan>{});
    case Metric::chebyshev: return with_dims(std::integral_constant<Metric, Metric::chebyshev>{});
  }
}

/// Which build kernels run: per cell (cell_kernel.cuh, the default) or per point (a thread
/// per point, a warp per point for rows of 65-256, rows sorted after the fill). The per-point
/// kernels stay for comparison in the benchmark: HORIZON_CUDA_KERNELS=point.
bool per_cell_kernels() {
  static const bool cell = [] {
    const char* choice = std::getenv("HORIZON_CUDA_KERNELS");
    return !choice || std::strcmp(choice, "point") != 0;
  }();
  return cell;
}

template <Pass P, int Items>
void cell_pass(const DeviceIndexView& ix, const SearchOptions& o, const PassArgs& args, cudaStream_t stream) {
  with_shape(o.metric, ix.grid.dims, o.half, [&](auto m, auto d, auto h) {
    launch_cell_pass<P, Items, decltype(m)::value, decltype(d)::value, decltype(h)::value>(ix, args, stream);
  });
}

/// One thread per point in sorted order, so a warp's points share most of their candidates.
/// Counting writes counts[id] = |family|; filling writes the family of each point whose id is
/// in [first, last) at out[offsets[id] - base].
template <Metric M, int D, bool Half, bool Fill>
__global__ void point_families(DeviceIndexView ix, PassArgs a) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= ix.n) return;
  const point_id self = ix.order[p];
  if (self >= ix.queries) {
    if (!Fill) a.counts[self] = 0;
    return;
  }
  if (Fill && (self < a.first || self >= a.last)) return;
  const double xi = ix.x[p], yi = ix.y[p], zi = ix.z[p];
  const std::int64_t cx = ix.grid.cell_of(xi, 0), cy = ix.grid.cell_of(yi, 1);
  const std::int64_t cz = D == 3 ? ix.grid.cell_of(zi, 2) : 0;
  const int k = ix.grid.k, reach_z = D == 3 ? k : 0;
  point_id* row = Fill ? a.out + (a.offsets[self] - a.base) : nullptr;
  std::int64_t found = 0;
  for (int dz = -reach_z; dz <= reach_z; ++dz)
    for (int dy = -k; dy <= k; ++dy) {
      std::int64_t begin, end;
      ix.row(cx, cy + dy, cz + dz, begin, end);
      for (std::int64_t q = begin; q < end; ++q) {
        const double d = metric_accumulate<M>(xi - ix.x[q], yi - ix.y[q], D == 3 ? zi - ix.z[q] : 0.0);
        const point_id other = ix.order[q];
        const bool keep = Half ? other > self : q != p;
        if (d < a.threshold && keep) {
          if (Fill) row[found] = other;
          ++found;
        }
      }
    }
  if (!Fill) a.counts[self] = found;
}

template <bool Fill>
void point_pass(const DeviceIndexView& ix, const SearchOptions& o, const PassArgs& args, cudaStream_t stream) {
  with_shape(o.metric, ix.grid.dims, o.half, [&](auto m, auto d, auto h) {
    point_families<decltype(m)::value, decltype(d)::value, decltype(h)::value, Fill>
        <<<blocks_for(static_cast<std::size_t>(ix.n)), block_size, 0, stream>>>(ix, args);
    check_launch("point_families");
  });
}

/// Bits a radix sort of ids needs, with 2^bits - 1 free to pad with.
int id_bits(std::int64_t n) {
  int bits = 1;
  while ((std::int64_t{1} << bits) <= n) ++bits;
  return bits;
}

PassArgs pass_args(const SearchOptions& o, std::int64_t n) {
  PassArgs a{};
  a.threshold = metric_threshold(o.metric, o.horizon);
  a.sort_bits = id_bits(n);
  return a;
}

/// The count pass's results: row offsets by id, and what the fill needs to choose its kernel.
struct Counts {
  DeviceArray<std::int64_t> offsets;
  std::int64_t total = 0, longest = 0, widest = 0;  // entries, longest row, largest stencil
};

/// Counts each family, then an inclusive scan into offsets[1..n]; one synchronisation, to
/// read the totals the allocation of the list needs.
Counts count_offsets(const DeviceIndex& index, const SearchOptions& options, std::size_t count,
                     cudaStream_t stream, MemoryMeter& meter) {
  DeviceArray<std::int64_t> counts(count, meter), offsets(count + 1, meter), summary(3, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(summary.get(), 0, summary.bytes(), stream));
  PassArgs args = pass_args(options, index.size());
  args.counts = counts.get();
  args.widest = reinterpret_cast<unsigned long long*>(summary.get() + 2);
  if (per_cell_kernels()) cell_pass<Pass::count, wide_stage>(index.view(options.queries), options, args, stream);
  else point_pass<false>(index.view(options.queries), options, args, stream);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
  std::size_t temp_bytes = 0, max_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, temp_bytes, counts.get(), offsets.get() + 1,
                                                   static_cast<std::int64_t>(count), stream));
  HORIZON_CUDA_CHECK(cub::DeviceReduce::Max(nullptr, max_bytes, counts.get(), summary.get() + 1,
                                            static_cast<std::int64_t>(count), stream));
  DeviceArray<char> temp(std::max(temp_bytes, max_bytes), meter);
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp.get(), temp_bytes, counts.get(), offsets.get() + 1,
                                                   static_cast<std::int64_t>(count), stream));
  HORIZON_CUDA_CHECK(cub::DeviceReduce::Max(temp.get(), max_bytes, counts.get(), summary.get() + 1,
                                            static_cast<std::int64_t>(count), stream));
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(summary.get(), offsets.get() + count, sizeof(std::int64_t),
                                     cudaMemcpyDeviceToDevice, stream));
  std::int64_t host[3];
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(host, summary.get(), sizeof(host), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  return Counts{std::move(offsets), host[0], host[1], host[2]};
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

constexpr int fused_min = 64;  // per-point kernels: longer rows take the fused kernel

// ---- Per-point kernels: fused fill and sort for rows of 65 to 256 ------------------------------
// A warp per point: lanes test 32 consecutive candidates at once (coalesced loads), ballot the
// hits into a row staged in shared memory, sort it in registers (cub::WarpMergeSort) and store it
// with coalesced writes. Nsight Compute on the two-kernel path (n = 200, m = 3.015, H100): the
// thread-per-point fill spent 21.5 ms on uncoalesced row stores, the warp sort 10.8 ms on
// blocked loads.

template <Metric M, int D, bool Half, int Items>
__global__ void __launch_bounds__(block_size) fill_sorted_rows(DeviceIndexView ix, PassArgs a) {
  constexpr int warps = block_size / 32, capacity = 32 * Items;
  using WarpSort = cub::WarpMergeSort<point_id, Items, 32>;
  __shared__ typename WarpSort::TempStorage temp[warps];
  __shared__ point_id staged[warps][capacity];
  const int warp = threadIdx.x / 32, lane = threadIdx.x % 32;
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(warps) + warp;
  if (p >= ix.n) return;
  const point_id self = ix.order[p];
  if (self >= ix.queries || self < a.first || self >= a.last) return;  // uniform across the warp
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
      found = sweep<M, D, Half, true>(xi, yi, zi, self, static_cast<int>(end - begin), a.threshold, row, found,
                                      [&](int i, double& x, double& y, double& z, point_id& id) {
                                        x = ix.x[begin + i];
                                        y = ix.y[begin + i];
                                        z = ix.z[begin + i];
                                        id = ix.order[begin + i];
                                      });
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
  point_id* destination = a.out + (a.offsets[self] - a.base);
  for (int at = lane; at < found; at += 32) destination[at] = row[at];
}

void fused_pass(const DeviceIndexView& ix, const SearchOptions& o, const PassArgs& args, std::int64_t longest,
                cudaStream_t stream) {
  const unsigned blocks = blocks_for(static_cast<std::size_t>(ix.n) * 32);
  with_shape(o.metric, ix.grid.dims, o.half, [&](auto m, auto d, auto h) {
    constexpr Metric M = decltype(m)::value;
    constexpr int D = decltype(d)::value;
    constexpr bool Half = decltype(h)::value;
    if (longest <= 128) fill_sorted_rows<M, D, Half, 4><<<blocks, block_size, 0, stream>>>(ix, args);
    else fill_sorted_rows<M, D, Half, 8><<<blocks, block_size, 0, stream>>>(ix, args);
    check_launch("fill_sorted_rows");
  });
}

/// Whether the fill itself leaves rows sorted (else they are sorted after it).
bool fill_sorts(const SearchOptions& options, const Counts& counts) {
  if (per_cell_kernels()) return counts.widest <= Stage<wide_stage>::capacity;
  return counts.longest > fused_min && counts.longest <= warp_row;
}

/// Whether the rows need the segmented sort and its second buffer.
bool needs_spare(const SearchOptions& options, const Counts& counts) {
  return options.sort_rows && !fill_sorts(options, counts) && counts.longest > block_row;
}

/// Fills (and sorts) the rows of ids [first, last): their entries go to rows_out, which holds
/// offsets[last] - offsets[first] entries; `spare` is as large when needs_spare() (the
/// segmented sort's second buffer). Returns the buffer holding the result.
point_id* fill_rows(const DeviceIndex& index, const SearchOptions& options, const Counts& counts,
                    std::int64_t base, std::int64_t entries, point_id first, point_id last, point_id* rows_out,
                    point_id* spare, cudaStream_t stream, MemoryMeter& meter) {
  if (entries == 0) return rows_out;
  const DeviceIndexView ix = index.view(options.queries);
  PassArgs args = pass_args(options, index.size());
  args.offsets = counts.offsets.get();
  args.out = rows_out;
  args.first = first;
  args.last = last;
  args.base = base;
  const bool sorting = options.sort_rows && fill_sorts(options, counts);
  if (per_cell_kernels()) {
    if (!sorting) cell_pass<Pass::fill, wide_stage>(ix, options, args, stream);
    else if (counts.widest <= Stage<2>::capacity) cell_pass<Pass::fill_sorted, 2>(ix, options, args, stream);
    else cell_pass<Pass::fill_sorted, wide_stage>(ix, options, args, stream);
  } else if (sorting) {
    fused_pass(ix, options, args, counts.longest, stream);
  } else {
    point_pass<true>(ix, options, args, stream);
  }
  if (!options.sort_rows || sorting) return rows_out;
  // Rows of up to 64 are cheaper with a thread per point and a sort after (measured, lattice
  // n = 400, m = 1.5: 0.074 s that way, 0.166 s with a warp per point).
  const std::int64_t rows = last - first;
  const std::int64_t* offsets = counts.offsets.get();
  if (counts.longest <= block_row) {
    sort_rows_on_chip(rows_out, offsets + first, base, rows, counts.longest, stream);
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

/// GPU memory a search can still take: free on the device plus what horizon's pool holds unused.
std::size_t available_device_bytes(const MemoryMeter& meter) {
  std::size_t free = 0, total = 0;
  HORIZON_CUDA_CHECK(cudaMemGetInfo(&free, &total));
  return free + pool_spare_bytes(meter.pool);
}

void select_device(int device) {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess || device >= count)
    throw Error("CUDA device " + std::to_string(device) + " does not exist (" +
                std::to_string(count) + " visible)");
  HORIZON_CUDA_CHECK(cudaSetDevice(device));
}

/// A stream per host thread and device, created once: creating one per search would cost a
/// synchronisation-free but measurable call each time.
cudaStream_t host_stream(int device) {
  thread_local cudaStream_t streams[64] = {};
  if (!streams[device]) HORIZON_CUDA_CHECK(cudaStreamCreateWithFlags(&streams[device], cudaStreamNonBlocking));
  return streams[device];
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
  const cudaStream_t stream = host_stream(options.device);
  MemoryMeter meter(options.device, stream);

  auto clock = std::chrono::steady_clock::now();
  DeviceArray<double> xyz(n * static_cast<std::size_t>(dims), meter);
  upload_coordinates(xyz.get(), points, stream);
  stats.host_to_device_seconds = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  const DeviceIndex index(xyz.get(), n, dims, options, stream, meter);
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  stats.grid_seconds = seconds_since(clock);
  xyz.reset();

  auto kernels = std::chrono::steady_clock::now();
  const Counts counts = count_offsets(index, options, n, stream, meter);
  double copy_seconds = 0;
  auto copy_start = std::chrono::steady_clock::now();
  Buffer<std::int64_t> host_offsets(n + 1);
  copy_to_host(host_offsets.data(), counts.offsets.get(), counts.offsets.bytes(), stream);
  Buffer<point_id> indices(static_cast<std::size_t>(counts.total));
  copy_seconds += seconds_since(copy_start);

  // Batches of rows sized to what is free: the list (twice when rows need the segmented sort).
  const std::size_t available = available_device_bytes(meter);
  const std::size_t reserve = std::size_t{256} << 20;
  const std::size_t usable = available > 2 * reserve ? available - reserve : available / 2;
  const std::int64_t fits = std::max<std::int64_t>(1, static_cast<std::int64_t>(usable / (3 * sizeof(point_id))));
  const std::int64_t batch_entries = options.gpu_batch_entries > 0 ? std::min(fits, options.gpu_batch_entries) : fits;
  for (std::size_t first = 0; first < n;) {
    // Rows up to the batch's size (a single larger row still goes alone).
    const std::int64_t limit = host_offsets[first] + batch_entries;
    std::size_t last = static_cast<std::size_t>(std::upper_bound(host_offsets.begin() + first + 1, host_offsets.end(), limit) -
                                                host_offsets.begin()) - 1;
    last = std::max(last, first + 1);
    const std::int64_t base = host_offsets[first], entries = host_offsets[last] - base;
    DeviceArray<point_id> rows(static_cast<std::size_t>(entries), meter);
    DeviceArray<point_id> spare(needs_spare(options, counts) ? static_cast<std::size_t>(entries) : 0, meter);
    const point_id* result = fill_rows(index, options, counts, base, entries, static_cast<point_id>(first),
                                       static_cast<point_id>(last), rows.get(), spare.get(), stream, meter);
    // While the GPU fills, the cores fault in the destination's pages.
    copy_start = std::chrono::steady_clock::now();
    parallel_touch(indices.data() + base, static_cast<std::size_t>(entries) * sizeof(point_id));
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

void DeviceNeighborList::Free::operator()(void* pointer) const { cudaFreeAsync(pointer, stream); }

NeighborList DeviceNeighborList::to_host(bool half) const {
  Buffer<std::int64_t> offsets(points_ + 1, 0);
  Buffer<point_id> indices(static_cast<std::size_t>(total_));
  if (offsets_) detail::copy_to_host(offsets.data(), offsets_.get(), offsets.size() * sizeof(std::int64_t), stream_);
  if (total_) detail::copy_to_host(indices.data(), indices_.get(), indices.size() * sizeof(point_id), stream_);
  return NeighborList(std::move(offsets), std::move(indices), half);
}

DeviceNeighborList search_device(const double* xyz, std::size_t count, int dims,
                                 const SearchOptions& options, cuda_stream stream, SearchStats* stats) {
  validate_horizon(options.horizon, options.cells_per_horizon);
  if (dims != 2 && dims != 3) throw Error("points must have 2 or 3 coordinates, not " + std::to_string(dims));
  DeviceNeighborList list;
  list.points_ = count;
  list.stream_ = stream;
  const DeviceNeighborList::Free free_on_stream{stream};
  detail::MemoryMeter meter(options.device, stream);
  if (count == 0) {
    detail::DeviceArray<std::int64_t> offsets(1, meter);
    HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
    list.offsets_ = {offsets.release(), free_on_stream};
    return list;
  }
  auto start = std::chrono::steady_clock::now();
  const detail::DeviceIndex index(xyz, count, dims, options, stream, meter);
  if (stats) {
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    stats->grid_seconds = detail::seconds_since(start);
    start = std::chrono::steady_clock::now();
  }
  detail::Counts counts = detail::count_offsets(index, options, count, stream, meter);
  list.total_ = counts.total;

  const bool spare_needed = detail::needs_spare(options, counts);
  const std::size_t list_bytes = static_cast<std::size_t>(list.total_) * sizeof(point_id);
  const std::size_t needed = (spare_needed ? 2 : 1) * list_bytes +
                             (spare_needed ? detail::sort_scratch_bytes(list.total_, static_cast<std::int64_t>(count), counts.offsets.get()) : 0);
  const std::size_t available = detail::available_device_bytes(meter);
  if (needed > available)
    throw DeviceOutOfMemory("the neighbour list needs " + std::to_string(needed) + " bytes of GPU memory, " +
                                std::to_string(available) + " are free (the host API builds it in batches)",
                            needed, available);
  detail::DeviceArray<point_id> rows(static_cast<std::size_t>(list.total_), meter);
  detail::DeviceArray<point_id> spare(spare_needed ? static_cast<std::size_t>(list.total_) : 0, meter);
  point_id* result = detail::fill_rows(index, options, counts, 0, list.total_, 0, static_cast<point_id>(count),
                                       rows.get(), spare.get(), stream, meter);
  list.indices_ = {result == rows.get() ? rows.release() : spare.release(), free_on_stream};
  list.offsets_ = {counts.offsets.release(), free_on_stream};
  if (stats) {
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    stats->backend = Backend::cuda;
    stats->search_seconds = detail::seconds_since(start);
    stats->kernel_seconds = stats->grid_seconds + stats->search_seconds;
    stats->peak_gpu_bytes = meter.peak;
  }
  return list;
}

void cuda_release_cached_memory(int device) {
  detail::select_device(device);
  HORIZON_CUDA_CHECK(cudaDeviceSynchronize());
  HORIZON_CUDA_CHECK(cudaMemPoolTrimTo(detail::device_pool(device), 0));
}

std::string cuda_device_name(int device) {
  cudaDeviceProp properties;
  if (cudaGetDeviceProperties(&properties, device) != cudaSuccess) return "";
  return properties.name;
}

}  // namespace horizon
