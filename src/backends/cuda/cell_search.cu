// The cell search (a periodic cell of any shape, per-entry outputs, self_interaction) for
// points in GPU memory, the CPU's method (core/cell_search.cpp) step by step on the device: the
// points wrapped into the cell and their images made with the CPU's functions
// (core/cell_images.hpp), the engine's query search of them all for the candidates, and each
// row walked twice, to count and then to write, by the CPU's own walk (core/cell_walk.hpp),
// compiled with -fmad=false: both keep the same entries with the same bits.
#include <cub/device/device_scan.cuh>

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "../../core/cell_images.hpp"
#include "../../core/cell_problem.hpp"
#include "../../core/cell_walk.hpp"
#include "device_list_access.hpp"
#include "device_memory.hpp"
#include "launch.cuh"

namespace horizon::detail {
namespace {

/// The reach of the images per axis, in cells (images_reach), passed by value.
struct Reach {
  double cells[3];
};

/// The largest |coordinate| (the bits of a non-negative double order as integers) and the
/// index of the first coordinate that is NaN or infinite.
__global__ void scan_coordinates(const double* xyz, std::size_t values, unsigned long long* largest,
                                 unsigned long long* first_bad) {
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  double most = 0;
  for (std::size_t v = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; v < values; v += stride) {
    if (isfinite(xyz[v])) most = fmax(most, fabs(xyz[v]));
    else atomicMin(first_bad, static_cast<unsigned long long>(v));
  }
  atomicMax(largest, static_cast<unsigned long long>(__double_as_longlong(most)));
}

/// Each point's wraps and fractional coordinates in the cell, and its image count at
/// first[i + 1]; the smallest index of a point too far from the cell lowers *too_far.
__global__ void wrap_points(const double* xyz, std::int64_t n, CellFrame frame, Reach reach, std::int32_t* wraps,
                            double* fractional, std::int64_t* first, unsigned long long* too_far) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  if (!wrap_into_cell(xyz + i * frame.dims, frame, reach.cells, wraps + i * 3, fractional + i * 3, first[i + 1]))
    atomicMin(too_far, static_cast<unsigned long long>(i));
}

/// The wrapped points at local[0, n), then point i's images from local[n + first[i]] on.
__global__ void place_images(const double* xyz, std::int64_t n, CellFrame frame, Reach reach,
                             const std::int32_t* wraps, const double* fractional, const std::int64_t* first,
                             double* local, point_id* image_of, std::int32_t* image_shift) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  const int dims = frame.dims;
  double* wrapped = local + i * dims;
  for (int a = 0; a < dims; ++a) wrapped[a] = xyz[i * dims + a] - cells_along(wraps + i * 3, frame, dims, a);
  write_images(wrapped, fractional + i * 3, static_cast<point_id>(i), frame, reach.cells,
               local + (n + first[i]) * dims, image_of + first[i], image_shift + first[i] * 3);
}

/// Row i's candidates walked (walk_row): counted into offsets[i + 1] when !Pick; else each kept
/// one picked, from offsets[i] on, as (i << 32 | its position in the row, ~0 for i itself).
/// A thread per row writes scattered; the entries' outputs are written by write_entries.
template <int D, Metric M, bool Pick>
__global__ void walk_rows(const std::int64_t* candidate_offsets, const point_id* candidates, std::int64_t n,
                          ImageTables tables, CellFrame frame, double threshold, bool half, bool self_interaction,
                          std::int64_t* offsets, std::uint64_t* picked) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  const auto limit = [threshold](point_id, point_id) { return threshold; };
  const point_id* row = candidates + candidate_offsets[i];
  const auto length = static_cast<std::size_t>(candidate_offsets[i + 1] - candidate_offsets[i]);
  std::int64_t at = Pick ? offsets[i] : 0;
  walk_row<D, M>(row, length, static_cast<point_id>(i), tables, frame, limit, half, self_interaction,
                 [&](const CellEntry&, std::int64_t position) {
                   if constexpr (Pick)
                     picked[at] = static_cast<std::uint64_t>(i) << 32 | static_cast<std::uint32_t>(position);
                   ++at;
                 });
  if constexpr (!Pick) offsets[i + 1] = at;
}

/// Where the entries' outputs go (null: not asked for).
struct EntryArrays {
  point_id* indices;
  std::int32_t* shifts;
  double* distances;
  double* vectors;
};

/// A thread per entry, so that neighbouring threads write neighbouring entries: each picked
/// candidate measured again (candidate_entry, the walk's own) and written.
template <int D, Metric M>
__global__ void write_entries(const std::uint64_t* picked, std::int64_t total, const std::int64_t* candidate_offsets,
                              const point_id* candidates, ImageTables tables, CellFrame frame, EntryArrays out) {
  const std::int64_t at = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (at >= total) return;
  const auto i = static_cast<point_id>(picked[at] >> 32);
  const auto position = static_cast<std::uint32_t>(picked[at]);
  CellEntry e;
  if (position == ~0u) self_entry<D, M>(i, tables, frame, e);
  else candidate_entry<D, M>(candidates[candidate_offsets[i] + position], i, tables, frame, e);
  out.indices[at] = e.j;
  for (int a = 0; a < D; ++a) {
    if (out.shifts) out.shifts[at * D + a] = e.shift[a];
    if (out.vectors) out.vectors[at * D + a] = e.vector[a];
  }
  if (out.distances) out.distances[at] = M == Metric::euclidean ? sqrt(e.accumulated) : e.accumulated;
}

/// offsets[1 .. n] summed in place (offsets[0] = 0), and the total read back.
std::int64_t scan_in_place(std::int64_t* offsets, std::int64_t n, cudaStream_t stream, MemoryMeter& meter) {
  HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets, 0, sizeof(std::int64_t), stream));
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, temp_bytes, offsets + 1, offsets + 1, n, stream));
  DeviceArray<char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp.get(), temp_bytes, offsets + 1, offsets + 1, n, stream));
  std::int64_t total = 0;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&total, offsets + n, sizeof(total), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  return total;
}

/// Throws as the host's check does for the first non-finite coordinate, read back from the GPU.
[[noreturn]] void throw_non_finite(const double* xyz, unsigned long long value, int dims, cudaStream_t stream) {
  double bad = 0;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&bad, xyz + value, sizeof(bad), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  throw Error("point " + std::to_string(value / static_cast<unsigned long long>(dims)) +
              " has a non-finite coordinate (" + std::to_string(bad) + ")");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

DeviceNeighborList DeviceListAccess::search_cell(const double* xyz, std::size_t count, int dims,
                                                 const SearchOptions& options, cuda_stream stream, SearchStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  const CellProblem problem = cell_problem(PointView(xyz, count, dims), options, {}, RadiusRule::gather);
  const PairOutputs& wanted = problem.outputs;
  MemoryMeter meter(options.device, stream, options.gpu_max_memory);
  const auto n = static_cast<std::int64_t>(count);
  DeviceArray<std::int64_t> offsets(count + 1, meter);
  DeviceNeighborList list;
  set(list, nullptr, nullptr, count, 0, stream);
  if (count == 0) {
    HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
    list.offsets_ = {offsets.release(), DeviceNeighborList::Free{stream}};
    set_geometry(list, wanted, dims, nullptr, nullptr, nullptr);
    return list;
  }

  // The points' extent sizes the margin that covers the rounding of wrapped and image points.
  const std::size_t values = count * static_cast<std::size_t>(dims);
  DeviceArray<unsigned long long> flags(3, meter);  // largest |x|, first non-finite, first too far
  const unsigned long long initial[3] = {0, ~0ull, ~0ull};
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(flags.get(), initial, sizeof(initial), cudaMemcpyHostToDevice, stream));
  scan_coordinates<<<std::min(blocks_for(values), 4096u), block_size, 0, stream>>>(xyz, values, flags.get(),
                                                                                    flags.get() + 1);
  check_launch("scan_coordinates");
  unsigned long long found[3];
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(found, flags.get(), sizeof(found), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  if (found[1] != ~0ull) throw_non_finite(xyz, found[1], dims, stream);
  double largest = 0;
  std::memcpy(&largest, &found[0], sizeof(largest));
  const double margin = image_margin(std::max(largest, problem.largest), problem);
  Reach reach;
  images_reach(problem, margin, reach.cells);

  // Wrapped points and their images, as on the CPU (make_images).
  DeviceArray<std::int32_t> wraps(count * 3, meter);
  DeviceArray<double> fractional(count * 3, meter);
  DeviceArray<std::int64_t> first(count + 1, meter);
  wrap_points<<<blocks_for(count), block_size, 0, stream>>>(xyz, n, problem.frame, reach, wraps.get(),
                                                            fractional.get(), first.get(), flags.get() + 2);
  check_launch("wrap_points");
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(found, flags.get(), sizeof(found), cudaMemcpyDeviceToHost, stream));
  const std::int64_t images = scan_in_place(first.get(), n, stream, meter);  // waits for both
  if (found[2] != ~0ull) throw Error("point " + std::to_string(found[2]) + " lies more than 2^30 cells away from the cell");
  if (static_cast<std::size_t>(images) + count >= static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error("cell: the points and their " + std::to_string(images) +
                " periodic images within the horizon must be fewer than 2^31 - 1 (a horizon of many cells?)");
  const std::size_t local_count = count + static_cast<std::size_t>(images);
  DeviceArray<double> local(local_count * static_cast<std::size_t>(dims), meter);
  DeviceArray<point_id> image_of(static_cast<std::size_t>(images), meter);
  DeviceArray<std::int32_t> image_shift(static_cast<std::size_t>(images) * 3, meter);
  place_images<<<blocks_for(count), block_size, 0, stream>>>(xyz, n, problem.frame, reach, wraps.get(),
                                                             fractional.get(), first.get(), local.get(), image_of.get(),
                                                             image_shift.get());
  check_launch("place_images");
  fractional.reset();
  first.reset();

  // The candidates: the engine's query search of the wrapped points among them all.
  SearchOptions inner = options;
  inner.horizon = problem.largest + margin;
  inner.half = false;
  inner.sort_rows = true;
  inner.queries = count;
  inner.box = {0, 0, 0};
  inner.cell = Cell{};
  inner.outputs = PairOutputs{};
  inner.self_interaction = false;
  const DeviceNeighborList candidates = search(local.get(), local_count, dims, inner, stream, nullptr, nullptr);
  if (stats) {
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    stats->grid_seconds = seconds_since(start);
  }
  const auto walked = std::chrono::steady_clock::now();

  // Each row walked twice: counted, then its kept candidates picked where the counts put them;
  // then the entries written, a thread each.
  const ImageTables tables{xyz, wraps.get(), image_of.get(), image_shift.get(), count};
  const double threshold = metric_threshold(problem.metric, problem.horizon);
  const auto walk = [&](auto d, auto m, auto pick, std::uint64_t* picked) {
    walk_rows<decltype(d)::value, decltype(m)::value, decltype(pick)::value>
        <<<blocks_for(count), block_size, 0, stream>>>(candidates.offsets(), candidates.indices(), n, tables,
                                                       problem.frame, threshold, problem.half,
                                                       problem.self_interaction, offsets.get(), picked);
  };
  with_dims_and_metric(dims, problem.metric, [&](auto d, auto m) { walk(d, m, std::false_type{}, nullptr); });
  check_launch("walk_rows (count)");
  const std::int64_t total = scan_in_place(offsets.get(), n, stream, meter);

  const auto entries = static_cast<std::size_t>(total), d = static_cast<std::size_t>(dims);
  const std::size_t entry_bytes = sizeof(point_id) + (wanted.shifts ? d * sizeof(std::int32_t) : 0) +
                                  (wanted.distances ? sizeof(double) : 0) + (wanted.vectors ? d * sizeof(double) : 0);
  const std::size_t needed = entries * (sizeof(std::uint64_t) + entry_bytes);  // the picks, then the list
  const std::size_t available = available_device_bytes(meter);
  if (needed > available)
    throw DeviceOutOfMemory("the neighbour list and its outputs need " + std::to_string(needed) +
                                " bytes of GPU memory, " + std::to_string(available) +
                                " are free (the host API builds it in batches)",
                            needed, available);
  DeviceArray<std::uint64_t> picked(entries, meter);
  with_dims_and_metric(dims, problem.metric, [&](auto d, auto m) { walk(d, m, std::true_type{}, picked.get()); });
  check_launch("walk_rows (pick)");
  DeviceArray<point_id> indices(entries, meter);
  DeviceArray<std::int32_t> shifts(wanted.shifts ? entries * d : 0, meter);
  DeviceArray<double> distances(wanted.distances ? entries : 0, meter), vectors(wanted.vectors ? entries * d : 0, meter);
  const EntryArrays out{indices.get(), shifts.get(), distances.get(), vectors.get()};
  if (entries > 0) {
    with_dims_and_metric(dims, problem.metric, [&](auto d, auto m) {
      write_entries<decltype(d)::value, decltype(m)::value><<<blocks_for(entries), block_size, 0, stream>>>(
          picked.get(), total, candidates.offsets(), candidates.indices(), tables, problem.frame, out);
    });
    check_launch("write_entries");
  }
  picked.reset();

  list.total_ = total;
  list.offsets_ = {offsets.release(), DeviceNeighborList::Free{stream}};
  list.indices_ = {indices.release(), DeviceNeighborList::Free{stream}};
  set_geometry(list, wanted, dims, shifts.release(), distances.release(), vectors.release());
  if (stats) {
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    stats->backend = Backend::cuda;
    stats->search_seconds = seconds_since(walked);
    stats->kernel_seconds = stats->grid_seconds + stats->search_seconds;
    stats->peak_gpu_bytes = meter.peak;
  }
  return list;
}

}  // namespace horizon::detail
