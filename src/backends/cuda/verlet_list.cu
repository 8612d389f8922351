// The device Verlet list: candidates from search_device at horizon + skin, then per refresh a
// count pass, a scan and a fill pass over them, a group of 8-32 lanes per row (its lanes read
// consecutive candidates, so the loads are coalesced and the kept ids are written in order by a
// ballot).
#include <cub/block/block_scan.cuh>
#include <cub/device/device_scan.cuh>
#include <cuda/atomic>

#include <cmath>

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

/// Row i's candidates within the horizon, tested as the search tests them (row point minus
/// candidate), by a group of G lanes of a warp (lane `lane` of the group at bits `group` of
/// the warp); returns their number, and Fill writes their ids, in candidate order, from out.
template <Metric M, int D, int G, bool Fill>
__device__ std::int64_t refresh_row(const std::int64_t* candidate_offsets, const point_id* candidates,
                                    const double* xyz, std::size_t i, double limit, unsigned lane, unsigned group,
                                    point_id* out) {
  const unsigned base = threadIdx.x % 32 - lane;
  const double* p = xyz + D * i;
  const std::int64_t begin = candidate_offsets[i], end = candidate_offsets[i + 1];
  std::int64_t at = 0;
  for (std::int64_t first = begin; first < end; first += G) {
    const std::int64_t k = first + lane;
    bool keep = false;
    point_id j = 0;
    if (k < end) {
      j = candidates[k];
      const double* q = xyz + D * static_cast<std::size_t>(j);
      keep = metric_accumulate<M>(p[0] - q[0], p[1] - q[1], D == 3 ? p[2] - q[2] : 0.0) < limit;
    }
    const unsigned ballot = (__ballot_sync(group, keep) & group) >> base;
    if (Fill && keep) out[at + __popc(ballot & ((1u << lane) - 1))] = j;
    at += __popc(ballot);
  }
  return at;
}

template <int G>
__device__ unsigned group_mask() {
  const unsigned lane = threadIdx.x % G, base = threadIdx.x % 32 - lane;
  return (G == 32 ? 0xffffffffu : (1u << G) - 1) << base;
}

/// Count (sizes[i]) or fill (from offsets[i]) a row per group of G lanes: the two-pass refresh,
/// for lists whose candidates' size does not fit in the GPU's memory twice.
template <Metric M, int D, int G, bool Fill>
__global__ void refresh_rows(const std::int64_t* candidate_offsets, const point_id* candidates, const double* xyz,
                             std::size_t count, double limit, std::int64_t* sizes, const std::int64_t* offsets,
                             point_id* out) {
  const std::size_t i = (blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x) / G;
  if (i >= count) return;  // the whole group
  const unsigned lane = threadIdx.x % G;
  const std::int64_t size = refresh_row<M, D, G, Fill>(candidate_offsets, candidates, xyz, i, limit, lane,
                                                       group_mask<G>(), Fill ? out + offsets[i] : nullptr);
  if (!Fill && lane == 0) sizes[i] = size;
}

/// Rows per chunk of the one-pass refresh: four rows per group of a block.
template <int G>
constexpr int chunk_rows = verlet_block / G * 4;

/// Publishes the size of chunk `c` in status[c] and returns the sizes of chunks 0 .. c - 1
/// summed: a decoupled look-back (as CUB's one-pass scans), waiting only on chunks still
/// counting. status[c]: 0, then its size | counted, then the sum up to it | placed.
__device__ std::int64_t place_chunk(unsigned long long* status, std::size_t c, std::int64_t size) {
  constexpr unsigned long long counted = 1ull << 62, placed = 1ull << 63, value = counted - 1;
  cuda::atomic_ref<unsigned long long, cuda::thread_scope_device> mine(status[c]);
  mine.store(static_cast<unsigned long long>(size) | counted, cuda::memory_order_relaxed);
  std::int64_t before = 0;
  for (std::size_t p = c; p-- > 0;) {
    cuda::atomic_ref<unsigned long long, cuda::thread_scope_device> theirs(status[p]);
    unsigned long long state;
    while ((state = theirs.load(cuda::memory_order_relaxed)) == 0) __nanosleep(20);
    before += static_cast<std::int64_t>(state & value);
    if (state & placed) break;
  }
  mine.store(static_cast<unsigned long long>(before + size) | placed, cuda::memory_order_relaxed);
  return before;
}

/// The refresh in one pass: each block takes the next chunk of chunk_rows<G> rows (in order:
/// `next_chunk` counts them out, so a chunk's predecessors are running or done), counts its
/// rows' kept candidates, learns where the chunk starts (place_chunk), then tests the same
/// candidates again, now in its caches, and writes the kept ids and the rows' ends
/// (offsets[i + 1]). Count + fill read every candidate and its point from memory twice.
template <Metric M, int D, int G>
__global__ void __launch_bounds__(verlet_block)
    refresh_chunks(const std::int64_t* candidate_offsets, const point_id* candidates, const double* xyz,
                   std::size_t count, double limit, unsigned long long* next_chunk, unsigned long long* status,
                   std::int64_t* offsets, point_id* out) {
  constexpr int rows = chunk_rows<G>, groups = verlet_block / G;
  static_assert(rows <= verlet_block, "a thread per row for the chunk's scan");
  using Scan = cub::BlockScan<std::int64_t, verlet_block>;
  __shared__ typename Scan::TempStorage scan;
  __shared__ std::int64_t row_start[rows];  // a row's size, then where it starts in the chunk
  __shared__ std::int64_t chunk_start;
  __shared__ unsigned long long chunk;
  if (threadIdx.x == 0) chunk = atomicAdd(next_chunk, 1ull);
  __syncthreads();
  const std::size_t first = static_cast<std::size_t>(chunk) * rows;
  const unsigned lane = threadIdx.x % G, group = group_mask<G>();
  for (int r = static_cast<int>(threadIdx.x / G); r < rows; r += groups) {
    const std::size_t i = first + r;
    const std::int64_t size =
        i < count ? refresh_row<M, D, G, false>(candidate_offsets, candidates, xyz, i, limit, lane, group, nullptr) : 0;
    if (lane == 0) row_start[r] = size;
  }
  __syncthreads();
  std::int64_t before = 0, total = 0;
  Scan(scan).ExclusiveSum(threadIdx.x < rows ? row_start[threadIdx.x] : 0, before, total);
  if (threadIdx.x < rows) row_start[threadIdx.x] = before;
  if (threadIdx.x == 0) chunk_start = place_chunk(status, chunk, total);
  __syncthreads();
  for (int r = static_cast<int>(threadIdx.x / G); r < rows; r += groups) {
    const std::size_t i = first + r;
    if (i >= count) break;  // the whole group
    const std::int64_t at = chunk_start + row_start[r];
    const std::int64_t size = refresh_row<M, D, G, true>(candidate_offsets, candidates, xyz, i, limit, lane, group, out + at);
    if (lane == 0) offsets[i + 1] = at + size;
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

/// The refreshed list's offsets (count + 1) and ids, allocated from the meter's pool; G lanes
/// per row. In one pass into ids sized as the candidates (refresh_chunks) when the GPU has the
/// memory, else by count, scan and fill into ids of the exact size.
template <Metric M, int D, int G>
std::int64_t refresh_into(const DeviceNeighborList& candidates, const double* xyz, double horizon,
                          cudaStream_t stream, MemoryMeter& meter, DeviceArray<std::int64_t>& offsets,
                          DeviceArray<point_id>& ids) {
  const std::size_t count = candidates.size();
  const double limit = metric_threshold(M, horizon);
  offsets = DeviceArray<std::int64_t>(count + 1, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
  if (count == 0) return 0;
  std::int64_t total = 0;
  const auto most_ids = static_cast<std::size_t>(candidates.total());
  const std::size_t chunks = (count + chunk_rows<G> - 1) / chunk_rows<G>;
  if ((most_ids + 2 * chunks) * sizeof(point_id) < available_device_bytes(meter) / 2) {
    ids = DeviceArray<point_id>(most_ids, meter);
    DeviceArray<unsigned long long> status(chunks + 1, meter);  // the chunks' states, then the next chunk's number
    HORIZON_CUDA_CHECK(cudaMemsetAsync(status.get(), 0, status.bytes(), stream));
    refresh_chunks<M, D, G><<<static_cast<unsigned>(chunks), verlet_block, 0, stream>>>(
        candidates.offsets(), candidates.indices(), xyz, count, limit, status.get() + chunks, status.get(),
        offsets.get(), ids.get());
    HORIZON_CUDA_CHECK(cudaGetLastError());
    HORIZON_CUDA_CHECK(cudaMemcpyAsync(&total, offsets.get() + count, sizeof(total), cudaMemcpyDeviceToHost, stream));
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    return total;
  }
  const unsigned blocks = blocks_for(G * count);
  DeviceArray<std::int64_t> sizes(count, meter);
  refresh_rows<M, D, G, false><<<blocks, verlet_block, 0, stream>>>(candidates.offsets(), candidates.indices(), xyz,
                                                                    count, limit, sizes.get(), nullptr, nullptr);
  HORIZON_CUDA_CHECK(cudaGetLastError());
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, temp_bytes, sizes.get(), offsets.get() + 1, count, stream));
  DeviceArray<unsigned char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp.get(), temp_bytes, sizes.get(), offsets.get() + 1, count, stream));
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&total, offsets.get() + count, sizeof(total), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  ids = DeviceArray<point_id>(static_cast<std::size_t>(total), meter);
  if (total > 0)
    refresh_rows<M, D, G, true><<<blocks, verlet_block, 0, stream>>>(candidates.offsets(), candidates.indices(), xyz,
                                                                      count, limit, nullptr, offsets.get(), ids.get());
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
template <Metric M, int D>
struct RefreshInto {
  template <class... Args>
  std::int64_t operator()(const DeviceNeighborList& candidates, Args&... args) const {
    const double mean = candidates.size() ? static_cast<double>(candidates.total()) / candidates.size() : 0;
    if (mean <= 24) return refresh_into<M, D, 8>(candidates, args...);
    if (mean <= 64) return refresh_into<M, D, 16>(candidates, args...);
    return refresh_into<M, D, 32>(candidates, args...);
  }
};

}  // namespace
}  // namespace detail

DeviceVerletList::DeviceVerletList(const double* xyz, std::size_t count, int dims, const SearchOptions& options,
                                   double skin, cuda_stream stream)
    : options_(options), skin_(skin), dims_(dims), stream_(stream), built_at_(nullptr, DeviceNeighborList::Free{stream}) {
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
  list.total_ = detail::dispatch<detail::RefreshInto>(options_.metric, dims_, candidates_, xyz, options_.horizon,
                                                      stream_, meter, offsets, ids);
  const DeviceNeighborList::Free free_on_stream{stream_};
  list.offsets_ = {offsets.release(), free_on_stream};
  if (ids.size() > 0) list.indices_ = {ids.release(), free_on_stream};
  return list;
}

}  // namespace horizon
