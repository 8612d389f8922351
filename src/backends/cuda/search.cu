// The CUDA backend (thesis ch. 5, done the modern way): a binning step that sorts points by
// cell with CUB radix sort and builds a cell start table (device_index.cuh), then the build
// step in two passes, count -> scan -> fill, so no row has a fixed maximum and offsets are
// 64-bit. The count pass keeps its verdicts as hit bits (hit_bits.cuh), so the fill tests
// nothing again. The fill kernel follows what the count found: short rows staged and sorted
// per thread (point_kernel.cuh), longer ones per cell with the stencil's ids sorted once so
// rows come out sorted (cell_kernel.cuh), and, for stencils too wide to stage or when the bits
// did not fit in GPU memory, straight stores and a sort after (row_sort.cuh). The pair test is metric_accumulate(), compiled with
// -fmad=false, so every decision matches the CPU backends bit for bit. Memory comes from a
// pool kept between calls (device_memory.hpp); host copies go through pinned staging
// (host_copy.cuh).
#include <cub/cub.cuh>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <sstream>
#include <tuple>
#include <type_traits>
#include <vector>

#include "../../core/cell_search.hpp"
#include "../../core/memory_check.hpp"
#include "../backends.hpp"
#include "cell_kernel.cuh"
#include "device_index.cuh"
#include "device_list_access.hpp"
#include "device_memory.hpp"
#include "host_copy.cuh"
#include "launch.cuh"
#include "periodic_images.cuh"
#include "point_kernel.cuh"
#include "row_pieces.cuh"
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

#define HORIZON_SHAPE(m, d, h) decltype(m)::value, decltype(d)::value, decltype(h)::value

/// Bits a radix sort of ids needs, with 2^bits - 1 free to pad with.
int id_bits(std::int64_t n) {
  int bits = 1;
  while ((std::int64_t{1} << bits) <= n) ++bits;
  return bits;
}

PassArgs pass_args(const SearchOptions& o, std::int64_t n, std::int64_t name_bound) {
  PassArgs a{};
  a.threshold = metric_threshold(o.metric, o.horizon);
  a.sort_bits = id_bits(name_bound);
  a.position_last = n;
  return a;
}

/// The count pass's hit bits (hit_bits.cuh): point p's words from bits + offsets[p], p its sorted position.
struct HitBits {
  DeviceArray<std::int64_t> offsets;
  DeviceArray<unsigned> bits;
};

/// Space for every point's hit bits when they take at most a quarter of the GPU memory still
/// free, which leaves the list (or its batches) the rest; else none, and the fill tests again.
HitBits hit_bits_for(const DeviceIndexView& ix, cudaStream_t stream, MemoryMeter& meter) {
  const auto n = static_cast<std::size_t>(ix.n);
  HitBits hits{DeviceArray<std::int64_t>(n + 1, meter), DeviceArray<unsigned>(0, meter)};
  {
    DeviceArray<std::int64_t> words(n, meter);
    if (ix.grid.dims == 3) stencil_words<3><<<blocks_for(n), block_size, 0, stream>>>(ix, words.get());
    else stencil_words<2><<<blocks_for(n), block_size, 0, stream>>>(ix, words.get());
    check_launch("stencil_words");
    HORIZON_CUDA_CHECK(cudaMemsetAsync(hits.offsets.get(), 0, sizeof(std::int64_t), stream));
    std::size_t temp_bytes = 0;
    HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, temp_bytes, words.get(), hits.offsets.get() + 1, ix.n, stream));
    DeviceArray<char> temp(temp_bytes, meter);
    HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp.get(), temp_bytes, words.get(), hits.offsets.get() + 1, ix.n, stream));
  }
  std::int64_t total = 0;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&total, hits.offsets.get() + n, sizeof(total), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  if (static_cast<std::size_t>(total) * sizeof(unsigned) > available_device_bytes(meter) / 4) hits.offsets.reset();
  else hits.bits = DeviceArray<unsigned>(static_cast<std::size_t>(total), meter);
  return hits;
}

/// The count pass's results: row offsets by id, its hit bits, and what the fill needs to
/// choose its kernel.
struct Counts {
  DeviceArray<std::int64_t> offsets;
  std::int64_t total = 0, longest = 0, widest = 0;  // entries, longest row, largest stencil
  std::int64_t cells = 0;                            // occupied cells
  std::int64_t long_rows = 0;                        // rows longer than staged_row
  HitBits hits;
  RowPieces pieces;
};

/// Counts each family, then an inclusive scan into offsets[1..count] (the rows: the points
/// without the images); one synchronisation, to read the totals the allocation of the list needs.
Counts count_offsets(const DeviceIndex& index, const SearchOptions& options, std::size_t count,
                     cudaStream_t stream, MemoryMeter& meter) {
  const DeviceIndexView ix = index.view(options.queries);
  HitBits hits = hit_bits_for(ix, stream, meter);
  DeviceArray<std::int64_t> counts(static_cast<std::size_t>(index.size()), meter), offsets(count + 1, meter),
      summary(5, meter);
  DeviceArray<unsigned> piece_bounds(2 * row_pieces, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(summary.get(), 0, summary.bytes(), stream));
  PassArgs args = pass_args(options, index.size(), index.name_bound());
  args.counts = counts.get();
  args.widest = reinterpret_cast<unsigned long long*>(summary.get() + 2);
  args.long_rows = reinterpret_cast<unsigned long long*>(summary.get() + 4);
  args.bits = hits.bits.get();
  args.bit_offsets = hits.offsets.get();
  with_shape(options.metric, ix.grid.dims, options.half, [&](auto m, auto d, auto h) {
    const unsigned blocks = blocks_for(static_cast<std::size_t>(ix.n));  // images too: their counts are 0
    count_families<HORIZON_SHAPE(m, d, h)><<<blocks, block_size, 0, stream>>>(ix, args);
  });
  check_launch("count_families");
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
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(summary.get() + 3, ix.cell_count, sizeof(std::int64_t),
                                     cudaMemcpyDeviceToDevice, stream));
  RowPieces pieces;
  find_row_pieces(ix, static_cast<std::int64_t>(count), piece_bounds.get(), pieces, stream);
  std::int64_t host[5];
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(host, summary.get(), sizeof(host), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  return Counts{std::move(offsets), host[0], host[1], host[2], host[3], host[4], std::move(hits), pieces};
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

/// The fill kernel, by the longest row, the widest stencil and the points per occupied cell
/// the count pass found.
enum class Fill {
  short_rows,  // rows of up to staged_row staged and sorted per thread, a few longer ones
               // stored straight and sorted afterwards (point_kernel.cuh)
  per_cell,    // stencils of up to the stage's capacity sorted once per cell, rows of wider
               // ones stored straight and sorted afterwards (cell_kernel.cuh)
  per_point    // anything else, and without hit bits: the candidates tested again, straight
               // stores, rows sorted afterwards (row_sort.cuh)
};

// A cell's staging and sort pay off only when shared by enough points: with ~3 points per
// cell (random cloud, 8 M points, m = 1.5, H100) the per-cell fill took 3x the per-point one.
constexpr std::int64_t cell_fill_min_points = 8;
// The short-row fill takes rows longer than it stages when they are this rare: the clustered
// cloud's (8 M points, m = 1.5) few rows past 64 sent all 8 M rows to the per-point fill and
// sort, at 0.48x the naive kernel on an H100.
constexpr std::int64_t spill_max_fraction = 8;

Fill fill_kind(const Counts& counts) {
  if (!counts.hits.bits.get()) return Fill::per_point;
  if (counts.longest <= staged_row) return Fill::short_rows;
  const auto points = static_cast<std::int64_t>(counts.offsets.size()) - 1;
  if ((counts.widest <= Stage<wide_stage>::capacity || counts.longest <= block_row) &&
      points >= cell_fill_min_points * counts.cells)
    return Fill::per_cell;
  if (counts.longest <= block_row && counts.long_rows * spill_max_fraction <= points) return Fill::short_rows;
  return Fill::per_point;
}

/// Whether the rows need the segmented sort and its second buffer.
bool needs_spare(const SearchOptions& options, const Counts& counts) {
  return options.sort_rows && fill_kind(counts) == Fill::per_point && counts.longest > block_row;
}

/// Fills (and sorts) the rows of ids [first, last): their entries go to rows_out, which holds
/// offsets[last] - offsets[first] entries; `spare` is as large when needs_spare() (the
/// segmented sort's second buffer). Returns the buffer holding the result.
point_id* fill_rows(const DeviceIndex& index, const SearchOptions& options, const Counts& counts,
                    std::int64_t base, std::int64_t entries, point_id first, point_id last, point_id* rows_out,
                    point_id* spare, cudaStream_t stream, MemoryMeter& meter) {
  if (entries == 0) return rows_out;
  const DeviceIndexView ix = index.view(options.queries);
  PassArgs args = pass_args(options, index.size(), index.name_bound());
  args.offsets = counts.offsets.get();
  args.out = rows_out;
  args.first = first;
  args.last = last;
  std::tie(args.position_first, args.position_last) = counts.pieces.positions(first, last);
  args.base = base;
  args.bits = counts.hits.bits.get();
  args.bit_offsets = counts.hits.offsets.get();
  const bool sorted = options.sort_rows;
  const unsigned blocks = blocks_for(static_cast<std::size_t>(args.position_last - args.position_first));
  const Fill kind = fill_kind(counts);
  const bool use_widest_stage =
      kind == Fill::per_cell && sorted && counts.widest > Stage<wide_stage>::capacity;
  const int staged_up_to = use_widest_stage ? Stage<widest_stage>::capacity : Stage<wide_stage>::capacity;
  // The rows a fill stores unsorted: their number, then their ids (the short-row fill's long
  // rows; the per-cell fill's rows of cells whose stencil outgrows every stage).
  const bool spills = sorted && ((kind == Fill::short_rows && counts.long_rows > 0) ||
                                 (kind == Fill::per_cell && counts.widest > staged_up_to));
  const std::int64_t most_spilled = kind == Fill::short_rows ? counts.long_rows : last - first;
  DeviceArray<point_id> spilled(spills ? static_cast<std::size_t>(most_spilled) + 1 : 0, meter);
  if (spills) {
    args.spilled = spilled.get() + 1;
    args.spill_count = reinterpret_cast<unsigned*>(spilled.get());
    HORIZON_CUDA_CHECK(cudaMemsetAsync(spilled.get(), 0, sizeof(point_id), stream));
  }
  with_shape(options.metric, ix.grid.dims, options.half, [&](auto m, auto d, auto h) {
    switch (kind) {
      case Fill::short_rows:
        if (counts.longest <= 32) launch_short_rows<decltype(d)::value, 32>(ix, args, sorted, stream);
        else launch_short_rows<decltype(d)::value, staged_row>(ix, args, sorted, stream);
        return;
      case Fill::per_cell:
        if (!sorted) return launch_cell_fill<false, wide_stage, decltype(d)::value>(ix, args, stream);
        if (counts.widest <= Stage<2>::capacity) return launch_cell_fill<true, 2, decltype(d)::value>(ix, args, stream);
        if (!use_widest_stage) return launch_cell_fill<true, wide_stage, decltype(d)::value>(ix, args, stream);
        // Dense cells (a clustered cloud's centres) staged too, in a second launch with a stage
        // of 4096 (34 KB) that would leave the other cells a quarter of the blocks per SM.
        launch_cell_fill<true, wide_stage, decltype(d)::value>(ix, args, stream, 0, true);
        return launch_cell_fill<true, widest_stage, decltype(d)::value>(ix, args, stream, Stage<wide_stage>::capacity);
      case Fill::per_point:
        if (blocks == 0) return;
        fill_families<HORIZON_SHAPE(m, d, h)><<<blocks, block_size, 0, stream>>>(ix, args);
        return check_launch("fill_families");
    }
  });
  const std::int64_t rows = last - first;
  const std::int64_t* offsets = counts.offsets.get();
  if (spills) {
    const RowSet set{offsets + first, base, most_spilled, args.spilled, args.spill_count, first};
    sort_rows_on_chip(rows_out, set, kind == Fill::short_rows ? staged_row + 1 : 0, counts.longest, stream);
  }
  if (!sorted || kind != Fill::per_point) return rows_out;
  if (counts.longest <= block_row) {
    sort_rows_on_chip(rows_out, RowSet{offsets + first, base, rows}, 0, counts.longest, stream);
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

#undef HORIZON_SHAPE

void select_device(int device) {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess || device >= count)
    throw Error("CUDA device " + std::to_string(device) + " does not exist (" +
                std::to_string(count) + " visible)");
  HORIZON_CUDA_CHECK(cudaSetDevice(device));
}

/// A stream of `device` for one search, from a process-wide pool: the multi-device driver's
/// part threads are new at every call, and a stream per thread was created (and leaked) each time.
class StreamLease {
public:
  explicit StreamLease(int device) : device_(device) {
    std::lock_guard lock(mutex());
    std::vector<cudaStream_t>& spare = pool()[device];
    if (!spare.empty()) {
      stream_ = spare.back();
      spare.pop_back();
    } else {
      HORIZON_CUDA_CHECK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking));
    }
  }
  StreamLease(const StreamLease&) = delete;
  StreamLease& operator=(const StreamLease&) = delete;
  ~StreamLease() {
    std::lock_guard lock(mutex());
    pool()[device_].push_back(stream_);
  }
  cudaStream_t get() const { return stream_; }

private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static std::vector<cudaStream_t>* pool() {  // never destroyed, as the staging pool
    static auto* streams = new std::vector<cudaStream_t>[max_devices];
    return streams;
  }
  int device_;
  cudaStream_t stream_ = nullptr;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Index into xyz of the first coordinate that is NaN or infinite: lowered by each such one.
__global__ void first_non_finite(const double* xyz, std::size_t values, unsigned long long* first) {
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  for (std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; i < values; i += stride)
    if (!isfinite(xyz[i])) atomicMin(first, static_cast<unsigned long long>(i));
}

/// Throws as validate() does when an uploaded coordinate is NaN or infinite: tested on the GPU
/// (microseconds), where the host would read every point again; the host then names it.
void check_finite_on_device(const double* xyz, PointView points, cudaStream_t stream, MemoryMeter& meter) {
  const std::size_t values = points.size() * static_cast<std::size_t>(points.dims());
  if (values == 0) return;
  DeviceArray<unsigned long long> first(1, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(first.get(), 0xff, sizeof(unsigned long long), stream));
  first_non_finite<<<std::min(blocks_for(values), 4096u), block_size, 0, stream>>>(xyz, values, first.get());
  check_launch("first_non_finite");
  unsigned long long found = 0;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&found, first.get(), sizeof(found), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  if (found != ~0ull) check_finite(points, 0);  // throws, naming the first
}

}  // namespace

bool cuda_usable() {
  int count = 0;
  return cudaGetDeviceCount(&count) == cudaSuccess && count > 0;
}

/// A CUDA event of one call (creating one takes microseconds).
struct Event {
  cudaEvent_t event = nullptr;
  Event() { HORIZON_CUDA_CHECK(cudaEventCreateWithFlags(&event, cudaEventDisableTiming)); }
  Event(const Event&) = delete;
  Event& operator=(const Event&) = delete;
  ~Event() { cudaEventDestroy(event); }
};

/// Rows of ids [first, last).
struct IdRange {
  point_id first, last;
};

/// The pieces a list that fits on the GPU is filled in, each copied back while the next fills:
/// up to 8, of at least two staging buffers each, made of whole row pieces (row_pieces.cuh).
/// One piece when the rows take the segmented sort (`whole`: it sorts the list at once) or
/// when the points are not in spatial order: each piece would then visit most sorted positions.
std::vector<IdRange> list_pieces(const Counts& counts, point_id n, bool whole) {
  const std::size_t list_bytes = static_cast<std::size_t>(counts.total) * sizeof(point_id);
  const int wanted = whole ? 1 : static_cast<int>(std::clamp<std::size_t>(list_bytes / (2 * staging_bytes), 1, 8));
  const auto id_at = [&](int piece) {  // first id of row piece `piece`
    return static_cast<point_id>(std::min<std::int64_t>(n, counts.pieces.ids_per_piece * piece));
  };
  std::vector<IdRange> pieces;
  std::int64_t visited = 0;  // sorted positions the pieces visit together
  for (int i = 0; i < wanted; ++i) {
    pieces.push_back({id_at(i * row_pieces / wanted), i + 1 == wanted ? n : id_at((i + 1) * row_pieces / wanted)});
    const auto [lo, hi] = counts.pieces.positions(pieces.back().first, pieces.back().last);
    visited += hi - lo;
  }
  const auto [lo, hi] = counts.pieces.positions(0, n);
  if (2 * visited > 3 * (hi - lo)) return {{0, n}};
  return pieces;
}

// Host arrays in, host CSR out. The fill overlaps the copy back: pieces of a list that fits,
// batches of rows of one that does not.
NeighborList search_cuda(PointView points, const SearchOptions& options, SearchStats& stats) {
  select_device(options.device);
  stats.gpu_name = cuda_device_name(options.device);
  stats.threads = 1;
  const std::size_t n = points.size();
  const int dims = points.dims();
  if (options.device >= max_devices) throw Error("CUDA device " + std::to_string(options.device) + " is past the 64 supported");
  const StreamLease lease(options.device);  // outlives every array below, freed on its stream
  const cudaStream_t stream = lease.get();
  MemoryMeter meter(options.device, stream, options.gpu_max_memory);

  auto clock = std::chrono::steady_clock::now();
  DeviceArray<double> xyz(n * static_cast<std::size_t>(dims), meter);
  upload_coordinates(xyz.get(), points, stream);
  check_finite_on_device(xyz.get(), points, stream, meter);
  stats.host_to_device_seconds = seconds_since(clock);

  // A periodic box: the points checked against it, their images made beside them, each found
  // as its original.
  clock = std::chrono::steady_clock::now();
  PointsWithImages local{std::move(xyz), DeviceArray<point_id>(0, meter), 0};
  if (is_periodic(options)) {
    check_inside_box(local.xyz.get(), n, dims, options, stream, meter);
    local = append_images_on_device(local.xyz.get(), n, PeriodicBox(options, dims), stream, meter);
  }
  const DeviceIndex index(local.xyz.get(), n + local.images, dims, options, stream, meter, local.images,
                          local.image_of.get());
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  stats.grid_seconds = seconds_since(clock);
  local = PointsWithImages{DeviceArray<double>(0, meter), DeviceArray<point_id>(0, meter), 0};

  auto kernels = std::chrono::steady_clock::now();
  const Counts counts = count_offsets(index, options, n, stream, meter);
  check_list_fits(counts.total, options);
  double copy_seconds = 0;
  Buffer<std::int64_t> host_offsets(n + 1);
  advise_huge_pages(host_offsets.data(), counts.offsets.bytes());
  Buffer<point_id> indices(static_cast<std::size_t>(counts.total));
  advise_huge_pages(indices.data(), indices.size() * sizeof(point_id));
  PinnedBlocks::get().prepare(host_offsets.data());
  PinnedBlocks::get().prepare(indices.data());

  // Batches of rows sized to what is free: the list (twice when rows need the segmented sort).
  const std::size_t available = available_device_bytes(meter);
  const std::size_t reserve = std::size_t{256} << 20;
  const std::size_t usable = available > 2 * reserve ? available - reserve : available / 2;
  const std::int64_t fits = std::max<std::int64_t>(1, static_cast<std::int64_t>(usable / (3 * sizeof(point_id))));
  const std::int64_t batch_entries = options.gpu_batch_entries > 0 ? std::min(fits, options.gpu_batch_entries) : fits;
  if (counts.total <= batch_entries) {
    // One batch, filled in pieces (list_pieces) on `stream` and copied back on a second one,
    // each piece as soon as it is written. The offsets go back first, while the first piece
    // fills (lattice 400, m = 1.5: the 512 MB of offsets take ~10 ms).
    const bool whole = needs_spare(options, counts);
    DeviceArray<point_id> rows(static_cast<std::size_t>(counts.total), meter);
    DeviceArray<point_id> spare(whole ? static_cast<std::size_t>(counts.total) : 0, meter);
    const std::vector<IdRange> pieces = list_pieces(counts, static_cast<point_id>(n), whole);
    const std::vector<Event> filled(pieces.size());
    const point_id* result = nullptr;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      result = fill_rows(index, options, counts, 0, counts.total, pieces[i].first, pieces[i].last, rows.get(),
                         spare.get(), stream, meter);
      HORIZON_CUDA_CHECK(cudaEventRecord(filled[i].event, stream));
    }
    const auto copy_start = std::chrono::steady_clock::now();
    const StreamLease side(options.device);
    copy_to_host(host_offsets.data(), counts.offsets.get(), counts.offsets.bytes(), side.get());
    std::vector<Written> written;
    for (std::size_t i = 0; i < pieces.size(); ++i)
      written.push_back({static_cast<std::size_t>(host_offsets[pieces[i].last]) * sizeof(point_id), filled[i].event});
    copy_to_host(indices.data(), result, static_cast<std::size_t>(counts.total) * sizeof(point_id), side.get(), written);
    copy_seconds = seconds_since(copy_start);
  } else {
    // Batches of rows, two on the GPU at once: batch i + 1 fills on `stream` while batch i is
    // copied back on a second one. Each takes up to half of batch_entries (a single larger row
    // still goes alone, and is then not overlapped with its neighbours).
    auto copy_start = std::chrono::steady_clock::now();
    copy_to_host(host_offsets.data(), counts.offsets.get(), counts.offsets.bytes(), stream);
    copy_seconds += seconds_since(copy_start);
    std::vector<IdRange> batches;
    for (std::size_t first = 0; first < n;) {
      const std::int64_t limit = host_offsets[first] + std::max<std::int64_t>(1, batch_entries / 2);
      const auto end = std::upper_bound(host_offsets.begin() + first + 1, host_offsets.end(), limit);
      const std::size_t last = std::max(static_cast<std::size_t>(end - host_offsets.begin()) - 1, first + 1);
      batches.push_back({static_cast<point_id>(first), static_cast<point_id>(last)});
      first = last;
    }
    const auto entries = [&](std::size_t i) { return host_offsets[batches[i].last] - host_offsets[batches[i].first]; };
    const StreamLease side(options.device);
    DeviceArray<point_id> rows[2] = {DeviceArray<point_id>(0, meter), DeviceArray<point_id>(0, meter)};
    DeviceArray<point_id> spare[2] = {DeviceArray<point_id>(0, meter), DeviceArray<point_id>(0, meter)};
    const point_id* result[2] = {};
    const Event filled[2];
    const auto fill = [&](std::size_t i) {  // into the buffers of batch i - 2, copied back by now
      const int b = static_cast<int>(i % 2);
      rows[b].reset();  // freed before the next is taken
      spare[b].reset();
      rows[b] = DeviceArray<point_id>(static_cast<std::size_t>(entries(i)), meter);
      spare[b] = DeviceArray<point_id>(needs_spare(options, counts) ? static_cast<std::size_t>(entries(i)) : 0, meter);
      result[b] = fill_rows(index, options, counts, host_offsets[batches[i].first], entries(i), batches[i].first,
                            batches[i].last, rows[b].get(), spare[b].get(), stream, meter);
      HORIZON_CUDA_CHECK(cudaEventRecord(filled[b].event, stream));
    };
    fill(0);
    for (std::size_t i = 0; i < batches.size(); ++i) {
      const bool overlap = i + 1 < batches.size() && entries(i) + entries(i + 1) <= batch_entries;
      if (overlap) fill(i + 1);
      copy_start = std::chrono::steady_clock::now();
      const auto bytes = static_cast<std::size_t>(entries(i)) * sizeof(point_id);
      const Written written{bytes, filled[i % 2].event};
      copy_to_host(indices.data() + host_offsets[batches[i].first], result[i % 2], bytes, side.get(), {&written, 1});
      copy_seconds += seconds_since(copy_start);
      if (!overlap && i + 1 < batches.size()) {
        rows[i % 2].reset();  // this batch's buffers go back first
        spare[i % 2].reset();
        fill(i + 1);
      }
    }
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
  detail::advise_huge_pages(indices.data(), indices.size() * sizeof(point_id));
  detail::PinnedBlocks::get().prepare(offsets.data());
  detail::PinnedBlocks::get().prepare(indices.data());
  if (offsets_) detail::copy_to_host(offsets.data(), offsets_.get(), offsets.size() * sizeof(std::int64_t), stream_);
  if (total_) detail::copy_to_host(indices.data(), indices_.get(), indices.size() * sizeof(point_id), stream_);
  NeighborList list(std::move(offsets), std::move(indices), half);
  if (!outputs_.any()) return list;
  const auto entries = static_cast<std::size_t>(total_), d = static_cast<std::size_t>(dims_);
  Buffer<std::int32_t> shifts(outputs_.shifts ? entries * d : 0);
  Buffer<double> distances(outputs_.distances ? entries : 0), vectors(outputs_.vectors ? entries * d : 0);
  for (void* host : {static_cast<void*>(shifts.data()), static_cast<void*>(distances.data()),
                     static_cast<void*>(vectors.data())})
    if (host) detail::PinnedBlocks::get().prepare(host);
  if (!shifts.empty()) detail::copy_to_host(shifts.data(), shifts_.get(), shifts.size() * sizeof(std::int32_t), stream_);
  if (!distances.empty())
    detail::copy_to_host(distances.data(), distances_.get(), distances.size() * sizeof(double), stream_);
  if (!vectors.empty()) detail::copy_to_host(vectors.data(), vectors_.get(), vectors.size() * sizeof(double), stream_);
  list.set_geometry(outputs_, std::move(shifts), std::move(distances), std::move(vectors), dims_);
  return list;
}

DeviceNeighborList search_device(const double* xyz, std::size_t count, int dims,
                                 const SearchOptions& options, cuda_stream stream, SearchStats* stats) {
  return detail::DeviceListAccess::search(xyz, count, dims, options, stream, stats, nullptr);
}

DeviceNeighborList detail::DeviceListAccess::search(const double* xyz, std::size_t count, int dims,
                                                    const SearchOptions& options, cuda_stream stream,
                                                    SearchStats* stats, const PartNaming* naming) {
  validate_horizon(options.horizon, options.cells_per_horizon);
  if (dims != 2 && dims != 3) throw Error("points must have 2 or 3 coordinates, not " + std::to_string(dims));
  if (detail::needs_cell_search(options)) return search_cell(xyz, count, dims, options, stream, stats);
  DeviceNeighborList list;
  list.points_ = count;
  list.stream_ = stream;
  const DeviceNeighborList::Free free_on_stream{stream};
  detail::MemoryMeter meter(options.device, stream, options.gpu_max_memory);
  if (count == 0) {
    detail::DeviceArray<std::int64_t> offsets(1, meter);
    HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
    list.offsets_ = {offsets.release(), free_on_stream};
    return list;
  }
  auto start = std::chrono::steady_clock::now();
  // A periodic box: the points checked against it, their images made beside them.
  detail::PointsWithImages local{detail::DeviceArray<double>(0, meter), detail::DeviceArray<point_id>(0, meter), 0};
  if (detail::is_periodic(options)) {
    detail::check_inside_box(xyz, count, dims, options, stream, meter);
    local = detail::append_images_on_device(xyz, count, detail::PeriodicBox(options, dims), stream, meter);
  }
  const detail::DeviceIndex index(local.images ? local.xyz.get() : xyz, count + local.images, dims, options, stream,
                                  meter, local.images, local.image_of.get(), naming);
  if (stats) {
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    stats->grid_seconds = detail::seconds_since(start);
    start = std::chrono::steady_clock::now();
  }
  detail::Counts counts = detail::count_offsets(index, options, count, stream, meter);
  list.total_ = counts.total;

  const std::size_t list_bytes = static_cast<std::size_t>(list.total_) * sizeof(point_id);
  const auto needed_bytes = [&] {
    const bool spare = detail::needs_spare(options, counts);
    return (spare ? 2 : 1) * list_bytes +
           (spare ? detail::sort_scratch_bytes(list.total_, static_cast<std::int64_t>(count), counts.offsets.get()) : 0);
  };
  std::size_t needed = needed_bytes(), available = detail::available_device_bytes(meter);
  if (needed > available && counts.hits.bits.get()) {  // the fill can do without the hit bits
    counts.hits.bits.reset();
    counts.hits.offsets.reset();
    needed = needed_bytes();
    available = detail::available_device_bytes(meter);
  }
  const bool spare_needed = detail::needs_spare(options, counts);
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

int cuda_use_device_of(const void* pointer) {
  cudaPointerAttributes attributes{};
  if (cudaPointerGetAttributes(&attributes, pointer) != cudaSuccess || (attributes.type != cudaMemoryTypeDevice && attributes.type != cudaMemoryTypeManaged)) {
    cudaGetLastError();  // clear the error a host pointer leaves behind
    std::ostringstream what;
    what << "points at " << pointer << " are not in CUDA device memory";
    throw Error(what.str());
  }
  HORIZON_CUDA_CHECK(cudaSetDevice(attributes.device));
  return attributes.device;
}

int cuda_device_count() {
  int count = 0;
  return cudaGetDeviceCount(&count) == cudaSuccess ? count : 0;
}

std::string cuda_device_name(int device) {
  cudaDeviceProp properties;
  if (cudaGetDeviceProperties(&properties, device) != cudaSuccess) return "";
  return properties.name;
}

}  // namespace horizon

// After the host path it shares streams, upload and staging with.
#include "device_part.cuh"
