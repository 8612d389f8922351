// The device Verlet list: candidates from search_device at horizon + skin, then per refresh a
// count pass, a scan and a fill pass over them, a group of 8-32 lanes per row (its lanes read
// consecutive candidates, so the loads are coalesced and the kept ids are written in order by a
// ballot).
#include <cub/block/block_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <cuda/functional>

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

/// The points in single precision (x, y, z, 0: one aligned 16-byte load) for a first test of
/// every candidate, and the largest |coordinate| (as the bits of a double, which order as
/// integers), which bounds their rounding. The refresh is bound by gathering the candidates'
/// points through L2 (a second test of a chunk's candidates from the caches, or four loads in
/// flight per lane, gained nothing: bench/results/h200_device_verlet_unroll_tried); the
/// 16-byte points take fewer sectors than 24-byte ones, and a single load instead of three.
template <int D>
__global__ void to_single(const double* xyz, std::size_t count, float4* single, unsigned long long* largest) {
  using Reduce = cub::BlockReduce<double, verlet_block>;
  __shared__ typename Reduce::TempStorage reduce;
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  double most = 0;
  if (i < count) {
    const double* p = xyz + D * i;
    const double z = D == 3 ? p[2] : 0.0;
    single[i] = make_float4(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(z), 0.0f);
    most = fmax(fmax(fabs(p[0]), fabs(p[1])), fabs(z));
    if (most != most) most = INFINITY;  // NaN: no single-precision verdicts at all
  }
  const double block_most = Reduce(reduce).Reduce(most, cuda::maximum<>{});
  if (threadIdx.x == 0) atomicMax(largest, static_cast<unsigned long long>(__double_as_longlong(block_most)));
}

/// Where the single-precision accumulated distance decides alone: below `in` the double test
/// keeps the pair, above `out` it drops it, in between (or always, when single precision cannot
/// resolve the horizon) the double test runs. Each coordinate is rounded by at most u·largest
/// (u = 2^-24), a difference by u of itself more, and the sums and squares by a few u of the
/// result: a margin of 8·u·largest per axis (three axes for Manhattan) and 16 u of the horizon
/// covers them, and the double test's own rounding (10^-16), many times over.
struct SingleBounds {
  float in, out;
};

template <Metric M>
__device__ SingleBounds single_bounds(double horizon, const unsigned long long* largest) {
  constexpr double u = 0x1p-24;
  const double most = __longlong_as_double(static_cast<long long>(*largest));
  const double axes = M == Metric::manhattan ? 3 : 1;
  const double lo = horizon * (1 - 16 * u) - 8 * u * most * axes, hi = horizon * (1 + 16 * u) + 8 * u * most * axes;
  if (!(most < 1e30) || !(lo > 0.5 * horizon)) return {-1.0f, INFINITY};  // every candidate in double
  if constexpr (M == Metric::euclidean)
    return {__double2float_rd(lo * lo * (1 - 16 * u)), __double2float_ru(hi * hi * (1 + 16 * u))};
  return {__double2float_rd(lo * (1 - 16 * u)), __double2float_ru(hi * (1 + 16 * u))};
}

template <Metric M>
__device__ float single_accumulate(float dx, float dy, float dz) {
  if constexpr (M == Metric::euclidean) return (dx * dx + dy * dy) + dz * dz;
  if constexpr (M == Metric::manhattan) return (fabsf(dx) + fabsf(dy)) + fabsf(dz);
  return fmaxf(fmaxf(fabsf(dx), fabsf(dy)), fabsf(dz));
}

/// Row i's candidates within the horizon, by a group of G lanes of a warp: each tested in
/// single precision (single_bounds), and those it cannot decide as the search tests them (row
/// point minus candidate, in double). Count: sizes[i]; Fill: their ids, in candidate order,
/// from offsets[i].
template <Metric M, int D, int G, bool Fill>
__global__ void refresh_rows(const std::int64_t* candidate_offsets, const point_id* candidates, const double* xyz,
                             const float4* single, const unsigned long long* largest, std::size_t count,
                             double horizon, double limit, std::int64_t* sizes, const std::int64_t* offsets, point_id* out) {
  const std::size_t i = (blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x) / G;
  const unsigned lane = threadIdx.x % G, base = threadIdx.x % 32 - lane;
  const unsigned group = (G == 32 ? 0xffffffffu : (1u << G) - 1) << base;
  if (i >= count) return;  // the whole group
  const SingleBounds bounds = single_bounds<M>(horizon, largest);
  const double* p = xyz + D * i;
  const float4 ps = single[i];
  const std::int64_t begin = candidate_offsets[i], end = candidate_offsets[i + 1];
  std::int64_t at = Fill ? offsets[i] : 0;
  for (std::int64_t first = begin; first < end; first += G) {
    const std::int64_t k = first + lane;
    bool keep = false;
    point_id j = 0;
    if (k < end) {
      j = candidates[k];
      const float4 qs = single[j];
      const float near = single_accumulate<M>(ps.x - qs.x, ps.y - qs.y, ps.z - qs.z);
      keep = near < bounds.in;
      if (!keep && !(near > bounds.out)) {
        const double* q = xyz + D * static_cast<std::size_t>(j);
        keep = metric_accumulate<M>(p[0] - q[0], p[1] - q[1], D == 3 ? p[2] - q[2] : 0.0) < limit;
      }
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
  const unsigned blocks = blocks_for(G * count);
  DeviceArray<std::int64_t> sizes(count, meter);
  offsets = DeviceArray<std::int64_t>(count + 1, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(offsets.get(), 0, sizeof(std::int64_t), stream));
  if (count == 0) return 0;
  DeviceArray<float4> single(count, meter);
  DeviceArray<unsigned long long> largest(1, meter);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(largest.get(), 0, largest.bytes(), stream));
  to_single<D><<<blocks_for(count), verlet_block, 0, stream>>>(xyz, count, single.get(), largest.get());
  HORIZON_CUDA_CHECK(cudaGetLastError());
  refresh_rows<M, D, G, false><<<blocks, verlet_block, 0, stream>>>(candidates.offsets(), candidates.indices(), xyz,
                                                                    single.get(), largest.get(), count, horizon,
                                                                    metric_threshold(M, horizon), sizes.get(), nullptr, nullptr);
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
                                                                      single.get(), largest.get(), count, horizon,
                                                                      metric_threshold(M, horizon), nullptr, offsets.get(), ids.get());
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
