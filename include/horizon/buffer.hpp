#pragma once
/// \file buffer.hpp
/// The storage of neighbour lists: a std::vector whose elements are not zeroed on resize. A list
/// is always written in full before it is read, and zeroing 470 MB of indices first took 0.19 s
/// of a 1.1 s search on one core; without it the pages are faulted in by the (parallel) fill.
/// The last six large blocks freed (32 MB or more each, up to a quarter of the machine's memory)
/// are kept for the next lists of about their size, and the largest working arrays (1 MB or
/// more, up to 16 of them and an eighth of the memory) for the next search's, so a search
/// repeated every time step does not fault its pages in again; release_cached_buffers() gives
/// them back. The CUDA host path page-locks a kept list block the second time it receives a list
/// (then copied into by DMA alone); such a block stays locked until it is given back.
#include <cstdlib>
#include <new>
#include <vector>

namespace horizon {

/// Frees the blocks kept for the next searches, if any (unlocking those the CUDA host path locked).
void release_cached_buffers();

namespace detail {
// malloc (32 MB or more advised huge pages), through the lists' pool from 32 MB, the working
// arrays' pool from 1 MB.
void* allocate_large(std::size_t bytes);
void release_large(void* pointer, std::size_t bytes) noexcept;
void* allocate_scratch(std::size_t bytes);
void release_scratch(void* pointer) noexcept;
std::size_t cached_buffer_bytes();  // held by both pools now
// Called with each block of 1 MB or more just before it goes back to the system (the CUDA
// backend unregisters the blocks it page-locked). One hook; returns the one it replaces.
using BlockReleaseHook = void (*)(void* block);
BlockReleaseHook set_block_release_hook(BlockReleaseHook hook);
}  // namespace detail

/// Allocates through the pool of lists when `List`, else through the pool of working arrays.
template <typename T, bool List = true>
struct UninitializedAllocator {
  using value_type = T;
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U, List>&) {}
  template <typename U>
  struct rebind {
    using other = UninitializedAllocator<U, List>;
  };

  T* allocate(std::size_t n) {
    if constexpr (List) return static_cast<T*>(detail::allocate_large(n * sizeof(T)));
    return static_cast<T*>(detail::allocate_scratch(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if constexpr (List) return detail::release_large(p, n * sizeof(T));
    detail::release_scratch(p);
  }
  /// Default construction leaves trivial elements uninitialised.
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const UninitializedAllocator<U, List>&) const { return true; }
};

template <typename T>
using Buffer = std::vector<T, UninitializedAllocator<T>>;

/// A search's working arrays (the cell index): not zeroed either, kept in their own pool, so
/// they do not take the place of the lists' blocks.
template <typename T>
using ScratchBuffer = std::vector<T, UninitializedAllocator<T, false>>;

}  // namespace horizon
