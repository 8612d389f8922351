#pragma once
// CUDA error checks that throw horizon::Error naming the call, and device arrays that count
// the GPU memory they hold so a search can report its peak.
#include <cuda_runtime.h>

#include <string>

#include "horizon/error.hpp"

namespace horizon::detail {

inline void cuda_check(cudaError_t status, const char* call, const char* file, int line) {
  if (status != cudaSuccess)
    throw Error(std::string("CUDA error in ") + call + " (" + file + ":" + std::to_string(line) +
                "): " + cudaGetErrorString(status));
}
#define HORIZON_CUDA_CHECK(call) ::horizon::detail::cuda_check((call), #call, __FILE__, __LINE__)

/// Bytes of GPU memory held through DeviceArray now and at most since reset.
struct MemoryMeter {
  std::size_t now = 0, peak = 0;
};

template <typename T>
class DeviceArray {
public:
  DeviceArray(std::size_t count, MemoryMeter& meter) : size_(count), meter_(&meter) {
    if (count == 0) return;
    HORIZON_CUDA_CHECK(cudaMalloc(&data_, count * sizeof(T)));
    meter_->now += bytes();
    meter_->peak = std::max(meter_->peak, meter_->now);
  }
  ~DeviceArray() { reset(); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray(DeviceArray&& other) noexcept
      : data_(other.data_), size_(other.size_), meter_(other.meter_) {
    other.data_ = nullptr;
    other.size_ = 0;
  }
  DeviceArray& operator=(DeviceArray&& other) noexcept {
    if (this != &other) {
      reset();
      data_ = other.data_;
      size_ = other.size_;
      meter_ = other.meter_;
      other.data_ = nullptr;
      other.size_ = 0;
    }
    return *this;
  }

  T* get() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t bytes() const { return size_ * sizeof(T); }
  /// Gives up ownership (the caller frees with cudaFree).
  T* release() {
    meter_->now -= bytes();
    T* data = data_;
    data_ = nullptr;
    size_ = 0;
    return data;
  }
  void reset() {
    if (!data_) return;
    meter_->now -= bytes();
    cudaFree(data_);
    data_ = nullptr;
    size_ = 0;
  }

private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
  MemoryMeter* meter_;
};

}  // namespace horizon::detail
