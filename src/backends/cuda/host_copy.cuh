#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// Host <-> device copies of pageable memory at close to pinned bandwidth: through two pinned
// staging buffers, the DMA engine moving one while all cores fill or empty the other. The
// buffers are allocated once and kept for later copies on any thread (pinning memory is slow).
#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "../../core/parallel_copy.hpp"
#include "device_memory.hpp"
#include "pinned_blocks.cuh"
#include "staging_chunks.hpp"

namespace horizon::detail {
namespace {

constexpr std::size_t staging_bytes = std::size_t{64} << 20;
constexpr int max_devices = 64;

/// Two pinned buffers (portable: pinned for every device's context) and, per device, an event
/// marking each one's last copy.
class Staging {
public:
  Staging() {
    HORIZON_CUDA_CHECK(cudaHostAlloc(reinterpret_cast<void**>(&base_), 2 * staging_bytes, cudaHostAllocPortable));
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  ~Staging() {
    for (auto& events : done_)
      for (auto& e : events)
        if (e) cudaEventDestroy(e);
    cudaFreeHost(base_);
  }
  char* buffer(int i) { return base_ + i * staging_bytes; }
  /// The event of buffer i on the current device.
  cudaEvent_t done(int i) {
    int device = 0;
    HORIZON_CUDA_CHECK(cudaGetDevice(&device));
    cudaEvent_t& e = done_[device][i];
    if (!e) HORIZON_CUDA_CHECK(cudaEventCreateWithFlags(&e, cudaEventDisableTiming));
    return e;
  }

private:
  char* base_ = nullptr;
  cudaEvent_t done_[max_devices][2] = {};
};

/// Staging buffers for the duration of one copy, taken from a process-wide pool and returned to
/// it: the multi-device driver runs each part on a new host thread, which with buffers per
/// thread pinned 128 MB afresh (and unpinned it at the thread's exit) at every call.
class StagingLease {
public:
  StagingLease() {
    std::lock_guard lock(mutex());
    if (!pool().empty()) {
      staging_ = std::move(pool().back());
      pool().pop_back();
    }
    if (!staging_) staging_ = std::make_unique<Staging>();
  }
  StagingLease(const StagingLease&) = delete;
  StagingLease& operator=(const StagingLease&) = delete;
  ~StagingLease() {
    std::lock_guard lock(mutex());
    pool().push_back(std::move(staging_));
  }
  Staging* operator->() { return staging_.get(); }
  Staging& operator*() { return *staging_; }

private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  // Never destroyed: the CUDA runtime may be torn down before static destructors run.
  static std::vector<std::unique_ptr<Staging>>& pool() {
    static auto* buffers = new std::vector<std::unique_ptr<Staging>>;
    return *buffers;
  }
  std::unique_ptr<Staging> staging_;
};

/// Bytes [0, bytes) of a device array are written once `event` has completed (on another stream).
struct Written {
  std::size_t bytes;
  cudaEvent_t event;
};

/// Device -> host: the GPU fills one staging buffer while all cores empty the other. While the
/// cores wait for the GPU (for the kernels that write `device`, then for each chunk) they fault
/// in the destination's pages ahead of the copy: faulting in fresh memory costs as much as the
/// copy itself, and waiting is otherwise idle time. With `written` (ascending), each chunk
/// waits for the first event whose bytes cover it, so the copy starts while later parts of
/// `device` are still being written.
void copy_to_host(void* host, const void* device, std::size_t bytes, cudaStream_t stream,
                  std::span<const Written> written = {}) {
  if (bytes == 0) return;
  if (PinnedBlocks::get().pinned(host, bytes)) {  // page-locked: by DMA alone, a copy per written part
    std::size_t at = 0;
    auto copy_up_to = [&](std::size_t end) {
      HORIZON_CUDA_CHECK(cudaMemcpyAsync(static_cast<char*>(host) + at, static_cast<const char*>(device) + at,
                                         end - at, cudaMemcpyDeviceToHost, stream));
      at = end;
    };
    for (const Written& w : written) {
      if (at >= bytes) break;
      HORIZON_CUDA_CHECK(cudaStreamWaitEvent(stream, w.event, 0));
      if (std::min(w.bytes, bytes) > at) copy_up_to(std::min(w.bytes, bytes));
    }
    if (at < bytes) copy_up_to(bytes);
    HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
    return;
  }
  constexpr std::size_t touch_step = std::size_t{32} << 20;
  auto* to = static_cast<char*>(host);
  std::size_t touched = 0;  // [0, touched) is faulted in or already copied: never touched again
  StagingLease s;
  const std::vector<StagedChunk> plan = staging_chunks(bytes, staging_bytes);
  const std::size_t chunks = plan.size();
  std::size_t waits_for = 0;  // the entry of `written` that covers the chunk issued last
  auto issue = [&](std::size_t c) {
    const auto [at, size] = plan[c];
    if (!written.empty()) {
      while (waits_for + 1 < written.size() && written[waits_for].bytes < at + size) ++waits_for;
      HORIZON_CUDA_CHECK(cudaStreamWaitEvent(stream, written[waits_for].event, 0));
    }
    HORIZON_CUDA_CHECK(cudaMemcpyAsync(s->buffer(c % 2), static_cast<const char*>(device) + at, size,
                                       cudaMemcpyDeviceToHost, stream));
    HORIZON_CUDA_CHECK(cudaEventRecord(s->done(c % 2), stream));
  };
  issue(0);
  for (std::size_t c = 0; c < chunks; ++c) {
    if (c + 1 < chunks) issue(c + 1);
    const auto [at, size] = plan[c];
    while (touched < bytes && cudaEventQuery(s->done(c % 2)) == cudaErrorNotReady) {
      const std::size_t step = std::min({touch_step, size, bytes - touched});  // no longer than the chunk's DMA
      parallel_touch(to + touched, step);
      touched += step;
    }
    HORIZON_CUDA_CHECK(cudaEventSynchronize(s->done(c % 2)));
    parallel_copy(to + at, s->buffer(c % 2), size);
    touched = std::max(touched, at + size);
  }
}

/// Host -> device of the points' coordinates as doubles (float32 promoted on the way): all
/// cores fill one staging buffer while the GPU takes the other.
void upload_coordinates(double* device, PointView points, cudaStream_t stream) {
  const std::size_t values = points.size() * static_cast<std::size_t>(points.dims());
  const std::vector<StagedChunk> plan = staging_chunks(values * sizeof(double), staging_bytes);
  StagingLease s;
  for (std::size_t c = 0; c < plan.size(); ++c) {
    const std::size_t first = plan[c].at / sizeof(double), count = plan[c].size / sizeof(double);
    auto* buffer = reinterpret_cast<double*>(s->buffer(c % 2));
    if (c >= 2) HORIZON_CUDA_CHECK(cudaEventSynchronize(s->done(c % 2)));  // its last upload is done
    parallel_copy_coordinates(buffer, points, first, count);
    HORIZON_CUDA_CHECK(cudaMemcpyAsync(device + first, buffer, count * sizeof(double), cudaMemcpyHostToDevice, stream));
    HORIZON_CUDA_CHECK(cudaEventRecord(s->done(c % 2), stream));
  }
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
}

}  // namespace
}  // namespace horizon::detail
