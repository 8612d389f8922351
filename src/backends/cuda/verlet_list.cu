// The device Verlet list: candidates from search_device at horizon + skin, then per refresh a
// count pass, a scan and a fill pass over them, a group of 8-32 lanes per row (its lanes read
// consecutive candidates, so the loads are coalesced and the kept ids are written in order by a
// ballot).
#include <cub/device/device_scan.cuh>

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
/// candidate), by a group of G lanes of a warp. Count: sizes[i]; Fill: their ids, in candidate
/// order, from offsets[i].
template <Metric M, int D, int G, bool Fill>
__global__ void refresh_rows(const std::int64_t* candidate_offsets, const point_id* candidates, const double* xyz,
                             std::size_t count, double limit, std::int64_t* sizes, const std::int64_t* offsets,
                             point_id* out) {
  const std::size_t i = (blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x) / G;
  const unsigned lane = threadIdx.x % G, base = threadIdx.x % 32 - lane;
  const unsigned group = (G == 32 ? 0xffffffffu : (1u << G) - 1) << base;
  if (i >= count) return;  // the whole group
  const double* p = xyz + D * i;
  const std::int64_t begin = candidate_offsets[i], end = candidate_offsets[i + 1];
  std::int64_t at = Fill ? offsets[i] : 0;
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
  if (!Fill && lane == 0) sizes[i] = at;
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
/// per row.
template <Metric M, int D, int G>
std::int64_t refresh_into(const DeviceNeighborList& candidates, const double* xyz, double horizon,
                          cudaStream_t stream, MemoryMeter& meter, DeviceArray<std::int64_t>& offsets,
                          DeviceArray<point_id>& ids) {
  const std::size_t count = candidates.size();
  const double limit = metric_threshold(M, horizon);
  const unsigned blocks = blocks_for(G * count);
  DeviceArray<std::int64_t> sizes(count, meter);
  offsets = DeviceArray<std::int64_t>(count + 1, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
  if (count == 0) return 0;
  refresh_rows<M, D, G, false><<<blocks, verlet_block, 0, stream>>>(candidates.offsets(), candidates.indices(), xyz,
                                                                    count, limit, sizes.get(), nullptr, nullptr);
  HORIZON_CUDA_CHECK(cudaGetLastError());
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, temp_bytes, sizes.get(), offsets.get() + 1, count, stream));
  DeviceArray<unsigned char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp.get(), temp_bytes, sizes.get(), offsets.get() + 1, count, stream));
  std::int64_t total = 0;
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
