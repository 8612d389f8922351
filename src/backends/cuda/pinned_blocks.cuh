#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// Host blocks of the lists' pools (horizon/buffer.hpp) page-locked for the host path, so that a
// list is copied into them by DMA straight from the GPU: through pinned staging the host's
// memory moves each byte three times (the DMA into staging, the cores' read and write), and
// that, not PCIe, bounded the copy on the H100 machine's host (staged, lattice 200 at m = 1.5:
// 635 MB in 14.2 ms, 1.3x the PCIe time). A block is registered when it receives a list for
// the second time, when the pool hands it back for another search (a solver's next step): on
// a first call, pinning fresh memory costs more than the staged copy's faults. It stays
// registered while the pool holds it and is unregistered before the pool frees it. (H100 host,
// lattice 200, m = 1.5: list out 14.5 -> 11.5 ms; the call that registers takes about twice a
// repeated one; bench/results/pinned_lists_1206.)
#include <cuda_runtime.h>
#include <malloc.h>

#include <cstddef>
#include <iterator>
#include <map>
#include <mutex>
#include <set>

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
  /// list: registers it if it received one before.
  void prepare(void* block) {
    constexpr std::size_t smallest = std::size_t{32} << 20;  // the lists' pool's blocks
    const std::size_t bytes = malloc_usable_size(block);
    if (bytes < smallest) return;
    std::lock_guard lock(mutex_);
    if (registered_.count(block) || refused_.count(block)) return;
    if (seen_.insert(block).second) return;  // first list: staged
    if (cudaHostRegister(block, bytes, cudaHostRegisterPortable) == cudaSuccess) {
      registered_[block] = bytes;
    } else {
      cudaGetLastError();  // not sticky: clear it, and copy through staging as before
      refused_.insert(block);
    }
  }

  /// Whether [at, at + bytes) lies in a registered block.
  bool pinned(const void* at, std::size_t bytes) {
    std::lock_guard lock(mutex_);
    auto after = registered_.upper_bound(const_cast<void*>(at));
    if (after == registered_.begin()) return false;
    const auto& [block, size] = *std::prev(after);
    return static_cast<const char*>(at) + bytes <= static_cast<const char*>(block) + size;
  }

private:
  static void released(void* block) {
    PinnedBlocks& self = get();
    std::lock_guard lock(self.mutex_);
    if (self.registered_.erase(block)) cudaHostUnregister(block);  // errors ignored: the runtime may be gone at exit
    self.seen_.erase(block);
    self.refused_.erase(block);
  }
  std::mutex mutex_;
  std::map<void*, std::size_t> registered_;
  std::set<void*> seen_, refused_;
};

}  // namespace
}  // namespace horizon::detail
