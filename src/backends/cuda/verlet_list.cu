// The device Verlet list: candidates from search_device at horizon + skin, then per refresh a
// pass that tests them and keeps its verdicts as bits, a scan of the row sizes and a pass that
// writes the marked ids; a group of 8-32 lanes per row (its lanes read consecutive candidates, so
// the loads are coalesced and the kept ids are written in order by a ballot).
#include <cub/device/device_scan.cuh>

#include <cmath>
#include <type_traits>

#include "device_memory.hpp"
#include "horizon/device_verlet_list.hpp"
#include "horizon/metric.hpp"
#include "../../core/reference_search.hpp"

namespace horizon {
namespace detail {
namespace {

constexpr int verlet_block = 256;

/// moved = 1 when a point is at `threshold` or farther (accumulated metric) from where it was.
template <Metric M, int D>
__global__ void find_moved(const double* now, const double* then, std::size_t count, double threshold, int* moved) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i >= count) return;
  const double* a = now + D * i;
  const double* b = then + D * i;
  if (!(metric_accumulate<M>(a[0] - b[0], a[1] - b[1], D == 3 ? a[2] - b[2] : 0.0) < threshold)) *moved = 1;
}

/// The verdicts of one step of a group of G lanes over a row's candidates, one bit a lane.
template <int G>
using Marks = std::conditional_t<G == 8, std::uint8_t, std::conditional_t<G == 16, std::uint16_t, std::uint32_t>>;

/// Where row i's marks start: a row of s candidates takes ceil(s / G) <= s / G + 1 steps, so
/// rows laid out from offset / G + i never overlap, and no scan is needed.
template <int G>
__device__ std::size_t first_mark(std::int64_t candidate_offset, std::size_t i) {
  return static_cast<std::size_t>(candidate_offset / G) + i;
}

/// Count: row i's candidates within the horizon, tested as the search tests them (row point
/// minus candidate) by a group of G lanes of a warp; sizes[i] = how many, and each step's
/// verdicts kept in `marks`.
template <Metric M, int D, int G>
__global__ void mark_rows(const std::int64_t* candidate_offsets, const point_id* candidates, const double* xyz,
                          std::size_t count, double limit, std::int64_t* sizes, Marks<G>* marks) {
  const std::size_t i = (blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x) / G;
  const unsigned lane = threadIdx.x % G, base = threadIdx.x % 32 - lane;
  const unsigned group = (G == 32 ? 0xffffffffu : (1u << G) - 1) << base;
  if (i >= count) return;  // the whole group
  const double* p = xyz + D * i;
  const std::int64_t begin = candidate_offsets[i], end = candidate_offsets[i + 1];
  Marks<G>* row_marks = marks + first_mark<G>(begin, i);
  std::int64_t kept = 0;
  for (std::int64_t first = begin; first < end; first += G) {
    const std::int64_t k = first + lane;
    bool keep = false;
    if (k < end) {
      const double* q = xyz + D * static_cast<std::size_t>(candidates[k]);
      keep = metric_accumulate<M>(p[0] - q[0], p[1] - q[1], D == 3 ? p[2] - q[2] : 0.0) < limit;
    }
    const unsigned ballot = (__ballot_sync(group, keep) & group) >> base;
    if (lane == 0) row_marks[(first - begin) / G] = static_cast<Marks<G>>(ballot);
    kept += __popc(ballot);
  }
  if (lane == 0) sizes[i] = kept;
}

/// Fill: row i's marked candidates, in candidate order, from offsets[i]: the marks are read, not
/// the points again.
template <int G>
__global__ void write_marked_rows(const std::int64_t* candidate_offsets, const point_id* candidates, std::size_t count,
                                  const Marks<G>* marks, const std::int64_t* offsets, point_id* out) {
  const std::size_t i = (blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x) / G;
  const unsigned lane = threadIdx.x % G;
  if (i >= count) return;
  const std::int64_t begin = candidate_offsets[i], end = candidate_offsets[i + 1];
  const Marks<G>* row_marks = marks + first_mark<G>(begin, i);
  std::int64_t at = offsets[i];
  for (std::int64_t first = begin; first < end; first += G) {
    // Both loads issued at once: the id's waiting on the mark made the pass latency-bound.
    const point_id j = first + lane < end ? candidates[first + lane] : 0;
    const unsigned marked = row_marks[(first - begin) / G];
    if (marked >> lane & 1) out[at + __popc(marked & ((1u << lane) - 1))] = j;
    at += __popc(marked);
  }
}

unsigned blocks_for(std::size_t threads) {
  return static_cast<unsigned>((threads + verlet_block - 1) / verlet_block);
}

template <Metric M, int D>
bool moved_past(const double* now, const double* then, std::size_t count, double limit, cudaStream_t stream,
                MemoryMeter& meter) {
  DeviceArray<int> moved(1, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(moved.get(), 0, sizeof(int), stream));
  if (count > 0)
    find_moved<M, D><<<blocks_for(count), verlet_block, 0, stream>>>(now, then, count, metric_threshold(M, limit),
                                                                      moved.get());
  HORIZON_CUDA_CHECK(cudaGetLastError());
  int host = 0;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&host, moved.get(), sizeof(int), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  return host != 0;
}

/// Where a refresh keeps its row sizes, the scan's temporary storage and its marks: one block
/// allocated with the list and reused, so a refresh allocates only the list it returns.
struct Workspace {
  std::int64_t* sizes;
  void* scan;
  std::size_t scan_bytes;
  void* marks;
};

/// Bytes of the scan's temporary storage for `count` row sizes.
std::size_t scan_bytes(std::size_t count) {
  std::size_t bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, bytes, static_cast<const std::int64_t*>(nullptr),
                                                   static_cast<std::int64_t*>(nullptr), count));
  return bytes;
}

/// The refreshed list's offsets (count + 1) and ids, allocated from the meter's pool; G lanes
/// per row.
template <Metric M, int D, int G>
std::int64_t refresh_into(const DeviceNeighborList& candidates, const double* xyz, double horizon, const Workspace& work,
                          cudaStream_t stream, MemoryMeter& meter, DeviceArray<std::int64_t>& offsets,
                          DeviceArray<point_id>& ids) {
  const std::size_t count = candidates.size();
  const double limit = metric_threshold(M, horizon);
  const unsigned blocks = blocks_for(G * count);
  offsets = DeviceArray<std::int64_t>(count + 1, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
  if (count == 0) return 0;
  auto* marks = static_cast<Marks<G>*>(work.marks);
  mark_rows<M, D, G><<<blocks, verlet_block, 0, stream>>>(candidates.offsets(), candidates.indices(), xyz, count, limit,
                                                          work.sizes, marks);
  HORIZON_CUDA_CHECK(cudaGetLastError());
  std::size_t temp_bytes = work.scan_bytes;
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(work.scan, temp_bytes, work.sizes, offsets.get() + 1, count, stream));
  std::int64_t total = 0;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&total, offsets.get() + count, sizeof(total), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  ids = DeviceArray<point_id>(static_cast<std::size_t>(total), meter);
  if (total > 0)
    write_marked_rows<G><<<blocks, verlet_block, 0, stream>>>(candidates.offsets(), candidates.indices(), count,
                                                              marks, offsets.get(), ids.get());
  HORIZON_CUDA_CHECK(cudaGetLastError());
  return total;
}

/// f<M, D>(args...) for the run-time metric and dimension.
template <template <Metric, int> class F, class... Args>
auto dispatch(Metric metric, int dims, Args&&... args) {
  switch (metric) {
    case Metric::manhattan:
      return dims == 3 ? F<Metric::manhattan, 3>{}(args...) : F<Metric::manhattan, 2>{}(args...);
    case Metric::chebyshev:
      return dims == 3 ? F<Metric::chebyshev, 3>{}(args...) : F<Metric::chebyshev, 2>{}(args...);
    default:
      return dims == 3 ? F<Metric::euclidean, 3>{}(args...) : F<Metric::euclidean, 2>{}(args...);
  }
}

template <Metric M, int D>
struct MovedPast {
  template <class... Args>
  bool operator()(Args&... args) const { return moved_past<M, D>(args...); }
};

/// Lanes per row from the mean row length: short rows would leave most of a warp idle
/// (m = 1.5: 18 candidates a row).
int lanes_per_row(const DeviceNeighborList& candidates) {
  const double mean = candidates.size() ? static_cast<double>(candidates.total()) / candidates.size() : 0;
  return mean <= 24 ? 8 : mean <= 64 ? 16 : 32;
}

/// The bytes of a refresh's marks (a bit per candidate, and at most a step more per row).
std::size_t mark_bytes(const DeviceNeighborList& candidates) {
  const auto lanes = static_cast<std::size_t>(lanes_per_row(candidates));
  return (static_cast<std::size_t>(candidates.total()) / lanes + candidates.size()) * (lanes / 8);
}

template <Metric M, int D>
struct RefreshInto {
  template <class... Args>
  std::int64_t operator()(const DeviceNeighborList& candidates, Args&... args) const {
    switch (lanes_per_row(candidates)) {
      case 8: return refresh_into<M, D, 8>(candidates, args...);
      case 16: return refresh_into<M, D, 16>(candidates, args...);
      default: return refresh_into<M, D, 32>(candidates, args...);
    }
  }
};

}  // namespace
}  // namespace detail

DeviceVerletList::DeviceVerletList(const double* xyz, std::size_t count, int dims, const SearchOptions& options,
                                   double skin, cuda_stream stream)
    : options_(options), skin_(skin), dims_(dims), stream_(stream), built_at_(nullptr, DeviceNeighborList::Free{stream}),
      workspace_(nullptr, DeviceNeighborList::Free{stream}) {
  if (!(skin > 0) || !std::isfinite(skin)) throw Error("Verlet skin must be finite and > 0, not " + std::to_string(skin));
  if (detail::is_periodic(options))
    throw Error("a Verlet list in a periodic box is not supported: points wrapping across it break the skin bound");
  SearchOptions wide = options;
  wide.horizon = options.horizon + skin;
  candidates_ = search_device(xyz, count, dims, wide, stream);  // validates the dimension and horizon
  detail::MemoryMeter meter(options.device, stream);
  detail::DeviceArray<double> copy(count * static_cast<std::size_t>(dims), meter);
  if (copy.size() > 0)
    HORIZON_CUDA_CHECK(cudaMemcpyAsync(copy.get(), xyz, copy.bytes(), cudaMemcpyDeviceToDevice, stream));
  built_at_.reset(copy.release());
  // The refresh's workspace: row sizes, then the scan's storage, then the marks (each aligned).
  const std::size_t align = 256, rows = candidates_.size();
  const std::size_t scan_at = (rows * sizeof(std::int64_t) + align - 1) / align * align;
  const std::size_t scan = detail::scan_bytes(rows);
  const std::size_t marks_at = scan_at + (scan + align - 1) / align * align;
  detail::DeviceArray<unsigned char> work(marks_at + detail::mark_bytes(candidates_), meter);
  workspace_.reset(work.release());
  scan_at_ = scan_at;
  marks_at_ = marks_at;
}

bool DeviceVerletList::needs_rebuild(const double* xyz) const {
  // As VerletList: half the skin less a margin far above the rounding of distances.
  const double half_skin = 0.5 * skin_ - 1e-9 * (options_.horizon + skin_);
  detail::MemoryMeter meter(options_.device, stream_);
  return detail::dispatch<detail::MovedPast>(options_.metric, dims_, xyz, built_at_.get(), candidates_.size(),
                                             half_skin, stream_, meter);
}

DeviceNeighborList DeviceVerletList::refresh(const double* xyz) const {
  detail::MemoryMeter meter(options_.device, stream_);
  detail::DeviceArray<std::int64_t> offsets(0, meter);
  detail::DeviceArray<point_id> ids(0, meter);
  DeviceNeighborList list;
  list.points_ = candidates_.size();
  list.stream_ = stream_;
  unsigned char* work = workspace_.get();
  const detail::Workspace workspace{reinterpret_cast<std::int64_t*>(work), work + scan_at_, marks_at_ - scan_at_,
                                    work + marks_at_};
  list.total_ = detail::dispatch<detail::RefreshInto>(options_.metric, dims_, candidates_, xyz, options_.horizon,
                                                      workspace, stream_, meter, offsets, ids);
  const DeviceNeighborList::Free free_on_stream{stream_};
  list.offsets_ = {offsets.release(), free_on_stream};
  if (ids.size() > 0) list.indices_ = {ids.release(), free_on_stream};
  return list;
}

}  // namespace horizon
