// The cell search (a periodic cell of any shape, per-entry outputs, self_interaction) for
// points in GPU memory, the CPU's method (core/cell_search.cpp) step by step on the device: the
// points wrapped into the cell and their images made with the CPU's functions
// (core/cell_images.hpp), the engine's query search of them all for the candidates (a small
// system: every pair of points, j's copy and images as i's candidates), and each row walked
// twice, to count and then to pick, by the CPU's own walk (core/cell_walk.hpp), compiled with
// -fmad=false: both keep the same entries with the same bits.
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

/// What a kept candidate is picked as: i << 32 | its candidate id k (~0: i itself at S = 0).
__device__ std::uint64_t pick_of(std::int64_t i, point_id k, std::int64_t position) {
  return static_cast<std::uint64_t>(i) << 32 | (position < 0 ? ~0u : static_cast<std::uint32_t>(k));
}

/// Row i of the engine's list walked (walk_row): counted into offsets[i + 1] when !Pick; else
/// each kept candidate picked, from offsets[i] on. A thread per row.
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
                   if constexpr (Pick) picked[at] = pick_of(i, position < 0 ? 0 : row[position], position);
                   ++at;
                 });
  if constexpr (!Pick) offsets[i + 1] = at;
}

/// Point j's candidates in a small system: its wrapped copy (id j), then its images (ids
/// points + first[j] on, ascending G), as walk_row reads a row.
struct PointAndImages {
  point_id j, first_image;
  __device__ point_id operator[](std::size_t k) const { return k == 0 ? j : first_image + static_cast<point_id>(k) - 1; }
};

/// Pair (i, j) of a small system (a thread per pair, p = i * n + j): j's wrapped copy and
/// images walked as row i's candidates, counted into pair_offsets[p + 1] when !Pick, else
/// picked from pair_offsets[p] on. Row i is its n pairs in turn: (j, S) order.
template <int D, Metric M, bool Pick>
__global__ void walk_pairs(const std::int64_t* first, std::int64_t n, ImageTables tables, CellFrame frame,
                           double threshold, bool half, bool self_interaction, std::int64_t* pair_offsets,
                           std::uint64_t* picked) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= n * n) return;
  const std::int64_t i = p / n, j = p % n;
  const auto limit = [threshold](point_id, point_id) { return threshold; };
  const PointAndImages row{static_cast<point_id>(j), static_cast<point_id>(n + first[j])};
  const auto length = static_cast<std::size_t>(1 + first[j + 1] - first[j]);
  std::int64_t at = Pick ? pair_offsets[p] : 0;
  walk_row<D, M>(row, length, static_cast<point_id>(i), tables, frame, limit, half, self_interaction && i == j,
                 [&](const CellEntry&, std::int64_t position) {
                   if constexpr (Pick) picked[at] = pick_of(i, position < 0 ? 0 : row[position], position);
                   ++at;
                 });
  if constexpr (!Pick) pair_offsets[p + 1] = at;
}

/// Row i's offset: that of its first pair (i, 0).
__global__ void row_offsets_of_pairs(const std::int64_t* pair_offsets, std::int64_t n, std::int64_t* offsets) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i <= n) offsets[i] = pair_offsets[i * n];
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
__global__ void write_entries(const std::uint64_t* picked, std::int64_t total, ImageTables tables, CellFrame frame,
                              EntryArrays out) {
  const std::int64_t at = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (at >= total) return;
  const auto i = static_cast<point_id>(picked[at] >> 32);
  const auto k = static_cast<std::uint32_t>(picked[at]);
  CellEntry e;
  if (k == ~0u) self_entry<D, M>(i, tables, frame, e);
  else candidate_entry<D, M>(static_cast<point_id>(k), i, tables, frame, e);
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

/// A small system's rows are walked a thread per pair of points (walk_pairs): up to this many
/// pairs, and this many candidates in all (points times points and images).
constexpr std::size_t small_system_pairs = std::size_t{1} << 22, small_system_candidates = std::size_t{1} << 24;

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

  // The candidates. A small system walks a thread per pair of points (i, j), j's wrapped copy
  // and images as candidates: the engine's grid costs a dozen kernels and their waits (0.4-2.6
  // ms a call on an H100 for 1 to 4,096 atoms). A larger one runs the engine's query search of
  // the wrapped points among them all, a thread per row walking it.
  const bool small = count * count <= small_system_pairs && count * local_count <= small_system_candidates;
  DeviceNeighborList engine_rows;
  if (!small) {
    first.reset();
    SearchOptions inner = options;
    inner.horizon = problem.largest + margin;
    inner.half = false;
    inner.sort_rows = true;
    inner.queries = count;
    inner.box = {0, 0, 0};
    inner.cell = Cell{};
    inner.outputs = PairOutputs{};
    inner.self_interaction = false;
    engine_rows = search(local.get(), local_count, dims, inner, stream, nullptr, nullptr);
  }
  if (stats) {
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    stats->grid_seconds = seconds_since(start);
  }
  const auto walked = std::chrono::steady_clock::now();

  // Each row walked twice: counted, then its kept candidates picked where the counts put them;
  // then the entries written, a thread each.
  const ImageTables tables{xyz, wraps.get(), image_of.get(), image_shift.get(), count};
  const double threshold = metric_threshold(problem.metric, problem.horizon);
  DeviceArray<std::int64_t> pair_offsets(small ? count * count + 1 : 0, meter);
  const auto walk = [&](auto d, auto m, auto pick, std::uint64_t* picked) {
    constexpr int D = decltype(d)::value;
    constexpr Metric M = decltype(m)::value;
    constexpr bool Pick = decltype(pick)::value;
    if (small)
      walk_pairs<D, M, Pick><<<blocks_for(count * count), block_size, 0, stream>>>(
          first.get(), n, tables, problem.frame, threshold, problem.half, problem.self_interaction,
          pair_offsets.get(), picked);
    else
      walk_rows<D, M, Pick><<<blocks_for(count), block_size, 0, stream>>>(
          engine_rows.offsets(), engine_rows.indices(), n, tables, problem.frame, threshold, problem.half,
          problem.self_interaction, offsets.get(), picked);
  };
  with_dims_and_metric(dims, problem.metric, [&](auto d, auto m) { walk(d, m, std::false_type{}, nullptr); });
  check_launch("walk (count)");
  std::int64_t total = 0;
  if (small) {
    total = scan_in_place(pair_offsets.get(), n * n, stream, meter);
    row_offsets_of_pairs<<<blocks_for(count + 1), block_size, 0, stream>>>(pair_offsets.get(), n, offsets.get());
    check_launch("row_offsets_of_pairs");
  } else {
    total = scan_in_place(offsets.get(), n, stream, meter);
  }

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
  check_launch("walk (pick)");
  DeviceArray<point_id> indices(entries, meter);
  DeviceArray<std::int32_t> shifts(wanted.shifts ? entries * d : 0, meter);
  DeviceArray<double> distances(wanted.distances ? entries : 0, meter), vectors(wanted.vectors ? entries * d : 0, meter);
  const EntryArrays out{indices.get(), shifts.get(), distances.get(), vectors.get()};
  if (entries > 0) {
    with_dims_and_metric(dims, problem.metric, [&](auto d, auto m) {
      write_entries<decltype(d)::value, decltype(m)::value><<<blocks_for(entries), block_size, 0, stream>>>(
          picked.get(), total, tables, problem.frame, out);
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
