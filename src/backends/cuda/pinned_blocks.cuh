#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// Host blocks of the lists' pools (horizon/buffer.hpp) page-locked for the host path, so that a
// list is copied into them by DMA straight from the GPU: through pinned staging the host's
// memory moves each byte three times (the DMA into staging, the cores' read and write), and
// that, not PCIe, bounded the copy on the H100 machine's host (staged, lattice 200 at m = 1.5:
// 635 MB in 14.2 ms, 1.3x the PCIe time). A block is registered when it receives a list for
// the second time, when the pool hands it back for another search (a solver's next step): on
// a first call, pinning fresh memory costs more than the staged copy's faults. Registering
// runs on a thread of its own while that call copies through staging, as a first call does:
// pinning is serialised below the runtime (31 GB took 1.1-1.6 s on one thread or sixteen,
// bench/results/parallel_register_1206), and done inside the call it doubled it. Lists go by
// DMA from the first call that finds the registration complete. A block stays registered
// while the pool holds it and is unregistered before the pool frees it.
#include <cuda_runtime.h>
#include <malloc.h>

#include <atomic>
#include <cstddef>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "device_memory.hpp"
#include "horizon/buffer.hpp"

namespace horizon::detail {
namespace {

class PinnedBlocks {
public:
  static PinnedBlocks& get() {
    // Never destroyed: blocks may be released by static destructors.
    static auto* blocks = [] {
      auto* b = new PinnedBlocks;
      set_block_release_hook(&released);
      return b;
    }();
    return *blocks;
  }

  /// Called with a block of a list's pool (the pointer it was allocated at) about to receive a
  /// list: starts registering it, on a thread of its own, if it received one before.
  void prepare(void* block) {
    constexpr std::size_t smallest = std::size_t{32} << 20;  // the lists' pool's blocks
    const std::size_t bytes = malloc_usable_size(block);
    if (bytes < smallest) return;
    std::lock_guard lock(mutex_);
    if (blocks_.count(block)) return;
    if (seen_.insert(block).second) return;  // first list: staged
    int device = 0;
    HORIZON_CUDA_CHECK(cudaGetDevice(&device));
    auto& registration = *blocks_.emplace(block, std::make_unique<Registration>(bytes)).first->second;
    registration.worker = std::thread([block, bytes, device, &registration] {
      const bool locked = cudaSetDevice(device) == cudaSuccess &&
                          cudaHostRegister(block, bytes, cudaHostRegisterPortable) == cudaSuccess;
      if (!locked) cudaGetLastError();  // not sticky: clear it (this thread's); lists stay staged
      registration.state.store(locked ? State::registered : State::refused, std::memory_order_release);
    });
  }

  /// Whether [at, at + bytes) lies in a block whose registration has completed.
  bool pinned(const void* at, std::size_t bytes) {
    std::lock_guard lock(mutex_);
    auto after = blocks_.upper_bound(const_cast<void*>(at));
    if (after == blocks_.begin()) return false;
    const auto& [block, registration] = *std::prev(after);
    return registration->state.load(std::memory_order_acquire) == State::registered &&
           static_cast<const char*>(at) + bytes <= static_cast<const char*>(block) + registration->bytes;
  }

private:
  enum class State { registering, registered, refused };
  struct Registration {
    explicit Registration(std::size_t size) : bytes(size) {}
    std::size_t bytes;
    std::atomic<State> state{State::registering};
    std::thread worker;
  };

  static void released(void* block) {
    PinnedBlocks& self = get();
    std::lock_guard lock(self.mutex_);
    if (const auto found = self.blocks_.find(block); found != self.blocks_.end()) {
      Registration& registration = *found->second;
      registration.worker.join();  // the block must stay until its pages are locked, then unlocked
      if (registration.state.load() == State::registered)
        cudaHostUnregister(block);  // errors ignored: the runtime may be gone at exit
      self.blocks_.erase(found);
    }
    self.seen_.erase(block);
  }
  std::mutex mutex_;
  std::map<void*, std::unique_ptr<Registration>> blocks_;  // registering, registered or refused
  std::set<void*> seen_;
};

}  // namespace
}  // namespace horizon::detail
