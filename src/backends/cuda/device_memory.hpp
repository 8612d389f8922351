#pragma once
// CUDA error checks that throw horizon::Error naming the call, and device arrays drawn from
// a per-device stream-ordered memory pool that keeps freed memory for the next search (a
// solver searching every time step pays no cudaMalloc, cudaFree or implied synchronisation),
// counting the GPU memory they hold so a search can report its peak.
#include <cuda_runtime.h>

#include <bit>
#include <cstdint>
#include <mutex>
#include <string>

#include "horizon/error.hpp"

namespace horizon::detail {

inline void cuda_check(cudaError_t status, const char* call, const char* file, int line) {
  if (status != cudaSuccess)
    throw Error(std::string("CUDA error in ") + call + " (" + file + ":" + std::to_string(line) +
                "): " + cudaGetErrorString(status));
}
#define HORIZON_CUDA_CHECK(call) ::horizon::detail::cuda_check((call), #call, __FILE__, __LINE__)

/// horizon's memory pool on `device`, created on first use; it never returns memory to the
/// driver by itself (cuda_release_cached_memory() does).
inline cudaMemPool_t device_pool(int device) {
  constexpr int most_devices = 64;
  static std::mutex guard;
  static cudaMemPool_t pools[most_devices] = {};
  if (device < 0 || device >= most_devices) throw Error("CUDA device " + std::to_string(device) + " is out of range");
  std::lock_guard<std::mutex> lock(guard);
  if (!pools[device]) {
    cudaMemPoolProps props{};
    props.allocType = cudaMemAllocationTypePinned;
    props.location.type = cudaMemLocationTypeDevice;
    props.location.id = device;
    cuda_check(cudaMemPoolCreate(&pools[device], &props), "cudaMemPoolCreate", __FILE__, __LINE__);
    std::uint64_t keep_all = UINT64_MAX;
    cuda_check(cudaMemPoolSetAttribute(pools[device], cudaMemPoolAttrReleaseThreshold, &keep_all),
               "cudaMemPoolSetAttribute", __FILE__, __LINE__);
  }
  return pools[device];
}

/// Bytes the pool holds but no array uses: free for the next allocation from it.
inline std::size_t pool_spare_bytes(cudaMemPool_t pool) {
  std::uint64_t reserved = 0, used = 0;
  cuda_check(cudaMemPoolGetAttribute(pool, cudaMemPoolAttrReservedMemCurrent, &reserved), "cudaMemPoolGetAttribute", __FILE__, __LINE__);
  cuda_check(cudaMemPoolGetAttribute(pool, cudaMemPoolAttrUsedMemCurrent, &used), "cudaMemPoolGetAttribute", __FILE__, __LINE__);
  return static_cast<std::size_t>(reserved - used);
}

/// Bytes to take from the pool for an array of `bytes`: from 32 MB up, rounded up to one of
/// eight sizes per octave (DeviceArray does not round under a memory limit, which it could
/// pass). A solver's next list is a little longer or shorter than the one it frees; asked for
/// exactly, it may not fit the freed block, and the pool then maps fresh memory (4-5 ms for a
/// 3.7 GB list on an H200, as long as a Verlet refresh's kernels).
inline std::size_t pool_block_bytes(std::size_t bytes) {
  constexpr std::size_t rounded_from = std::size_t{32} << 20;
  if (bytes < rounded_from) return bytes;
  const std::size_t step = std::bit_floor(bytes) / 8;
  return (bytes + step - 1) / step * step;
}

/// Where a search's arrays come from (the device's pool, ordered on the search's stream), the
/// bytes they hold now and at most, and the most the search is to size itself to (0: no limit).
struct MemoryMeter {
  MemoryMeter(int device, cudaStream_t s, std::size_t most = 0) : pool(device_pool(device)), stream(s), limit(most) {}
  cudaMemPool_t pool;
  cudaStream_t stream;
  std::size_t limit;
  std::size_t now = 0, peak = 0;
};

template <typename T>
class DeviceArray {
public:
  DeviceArray(std::size_t count, MemoryMeter& meter) : size_(count), meter_(&meter) {
    if (count == 0) return;
    block_ = meter.limit ? bytes() : pool_block_bytes(bytes());
    HORIZON_CUDA_CHECK(cudaMallocFromPoolAsync(reinterpret_cast<void**>(&data_), block_, meter.pool, meter.stream));
    meter_->now += block_;
    meter_->peak = std::max(meter_->peak, meter_->now);
  }
  ~DeviceArray() { reset(); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray(DeviceArray&& other) noexcept
      : data_(other.data_), size_(other.size_), block_(other.block_), meter_(other.meter_) {
    other.data_ = nullptr;
    other.size_ = other.block_ = 0;
  }
  DeviceArray& operator=(DeviceArray&& other) noexcept {
    if (this != &other) {
      reset();
      data_ = other.data_;
      size_ = other.size_;
      block_ = other.block_;
      meter_ = other.meter_;
      other.data_ = nullptr;
      other.size_ = other.block_ = 0;
    }
    return *this;
  }

  T* get() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t bytes() const { return size_ * sizeof(T); }
  /// Gives up ownership (the caller frees with cudaFreeAsync on the meter's stream).
  T* release() {
    meter_->now -= block_;
    T* data = data_;
    data_ = nullptr;
    size_ = block_ = 0;
    return data;
  }
  void reset() {
    if (!data_) return;
    meter_->now -= block_;
    cudaFreeAsync(data_, meter_->stream);
    data_ = nullptr;
    size_ = block_ = 0;
  }

private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t block_ = 0;  ///< bytes taken from the pool (pool_block_bytes)
  MemoryMeter* meter_;
};

/// GPU memory a search can still take: free on the device plus what horizon's pool holds
/// unused, and no more than its limit (SearchOptions::gpu_max_memory) leaves.
inline std::size_t available_device_bytes(const MemoryMeter& meter) {
  std::size_t free = 0, total = 0;
  HORIZON_CUDA_CHECK(cudaMemGetInfo(&free, &total));
  const std::size_t available = free + pool_spare_bytes(meter.pool);
  if (meter.limit == 0) return available;
  return std::min(available, meter.limit > meter.now ? meter.limit - meter.now : 0);
}

}  // namespace horizon::detail
