#include "horizon/buffer.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <utility>

#include <malloc.h>
#include <unistd.h>

#include "parallel_copy.hpp"

namespace horizon::detail {

// Blocks of 32 MB or more (lists) are advised huge pages (madvise(MADV_HUGEPAGE), a hint): a
// first search faults in every page of its list, and on a virtual machine a 4 KB fault is
// expensive. 2-core AMD Zen 5 VM, `horizon search lattice:100 --horizon 0.3015` in a fresh
// process: search 1.0 s with 4 KB pages, 0.3-0.7 s advised (bench/results/page_faults_*).
// Smaller blocks (the cell index's arrays) are not: advised, the 16-core Xeon host's grid
// stalled 40-70 ms in 2 of 3 first calls (synchronous compaction under the THP defrag policy;
// an Intel VM of an earlier session saw the same for a list: 1.0 s advised, 0.16 s not).
//
// Freed large blocks (a search's offsets and indices, its working arrays) are kept in pools and
// handed to the next requests they fit: a solver that searches every step (free the old list,
// build the new one) otherwise faults in every page of every list again, which costs as much as
// copying the list out of a GPU (H200 host: 16 GB in 0.30-0.75 s against the 0.31 s PCIe copy).
namespace {

struct Block {
  void* pointer = nullptr;
  std::size_t bytes = 0;
};

/// Freed blocks kept for the next requests they fit (at most twice as large as asked).
struct Pool {
  static constexpr int most_slots = 16;
  Pool(std::size_t min, int count, int share) : min_bytes(min), slots(count), memory_share(share) {}
  const std::size_t min_bytes;  ///< smaller blocks go straight back to malloc
  const int slots;
  const int memory_share;  ///< at most 1/memory_share of the machine's memory is held back
  std::mutex mutex;
  Block block[most_slots];
};

// Lists: 32 MB and up (glibc maps larger blocks afresh at every malloc: its mmap threshold stops
// there): a search's offsets and indices, or the three lists of the max radius rule (the gather
// rows, their transpose, the union), which with two slots faulted in 0.8 GB again every call
// (clustered cloud of 10^6 points, 2-core Zen 5 VM: 2.2-2.3 s a call, 1.7-1.8 s with three);
// or a cell search's candidates and its ids, shifts, distances and vectors (six slots).
Pool& list_pool() {
  // Never destroyed: lists may be freed by static destructors.
  static auto* pool = new Pool(std::size_t{32} << 20, 6, 4);
  return *pool;
}

// Working arrays (the cell index, keys, images) and small lists: 16 KB and up. glibc gave them
// back to the system after every search (it trims the heap's top past 128 KB free) and faulted
// them in again at the next: 2-core AMD Zen 5 VM, lattice 100, m = 1.5, 2 threads, repeated
// searches: grid 0.10 s per call, 0.01 s from this pool; 2-core Zen 4 VM, 1,000 points, one
// core: a quarter of each call in the kernel, median 105-112 -> 88-90 us with 16 KB blocks kept.
Pool& scratch_pool() {
  static auto* pool = new Pool(std::size_t{16} << 10, 16, 8);
  return *pool;
}

std::atomic<BlockReleaseHook> release_hook{nullptr};

/// Gives a block back to the system, telling the hook first.
void free_block(void* pointer) noexcept {
  if (!pointer) return;
  if (auto* hook = release_hook.load(); hook && malloc_usable_size(pointer) >= scratch_pool().min_bytes) hook(pointer);
  std::free(pointer);
}

/// The machine's memory, read once (a system call: small searches give blocks back at every call).
std::size_t memory_bytes() {
  static const std::size_t bytes = [] {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(page) : 0;
  }();
  return bytes;
}

std::size_t held_limit(const Pool& pool) { return memory_bytes() / static_cast<std::size_t>(pool.memory_share); }

void* allocate_block(std::size_t bytes) {
  void* p = std::malloc(bytes ? bytes : 1);
  if (!p) throw std::bad_alloc();
  if (bytes >= list_pool().min_bytes) advise_huge_pages(p, bytes);
  return p;
}

/// Frees every block `pool` holds.
void empty(Pool& pool) {
  Block stale[Pool::most_slots];
  {
    std::lock_guard lock(pool.mutex);
    std::swap(stale, pool.block);
  }
  for (Block& b : stale) free_block(b.pointer);
}

/// A held block that fits, or a fresh one 1/16 larger than asked (address space only: untouched
/// pages cost nothing) so that the next search's arrays, a little longer, still fit. When none
/// fits, the list pool frees what it holds before taking more.
void* take(Pool& pool, std::size_t bytes, bool free_on_miss) {
  if (bytes < pool.min_bytes) return allocate_block(bytes);
  {
    std::lock_guard lock(pool.mutex);
    Block* fit = nullptr;  // the smallest block that holds `bytes` and is at most twice as large
    for (int s = 0; s < pool.slots; ++s) {
      Block& b = pool.block[s];
      if (b.pointer && b.bytes >= bytes && b.bytes / 2 <= bytes && (!fit || b.bytes < fit->bytes)) fit = &b;
    }
    if (fit) return std::exchange(*fit, Block{}).pointer;
  }
  if (free_on_miss) {
    empty(pool);
    empty(scratch_pool());
  }
  const std::size_t align = bytes >= list_pool().min_bytes ? std::size_t{2} << 20 : std::size_t{64} << 10;
  const std::size_t padded = (bytes + bytes / 16 + align - 1) / align * align;
  return allocate_block(padded);
}

/// Keeps `pointer` in place of the smallest block held, if it is larger and within the limit.
void give(Pool& pool, void* pointer) noexcept {
  const std::size_t bytes = pointer ? malloc_usable_size(pointer) : 0;  // a padded or reused block is larger than asked
  if (!pointer || bytes < pool.min_bytes) return free_block(pointer);
  {
    std::lock_guard lock(pool.mutex);
    std::size_t held = 0;
    Block* smallest = &pool.block[0];
    for (int s = 0; s < pool.slots; ++s) {
      Block& b = pool.block[s];
      held += b.bytes;
      if (b.bytes < smallest->bytes) smallest = &b;
    }
    if (bytes > smallest->bytes && held - smallest->bytes + bytes <= held_limit(pool))
      pointer = std::exchange(*smallest, Block{pointer, bytes}).pointer;
  }
  free_block(pointer);
}

std::size_t held_bytes(Pool& pool) {
  std::lock_guard lock(pool.mutex);
  std::size_t held = 0;
  for (const Block& b : pool.block) held += b.bytes;
  return held;
}

}  // namespace

// Lists below the lists' pool's size (a small search's, and every search's offsets) share the
// working arrays' pool.
void* allocate_large(std::size_t bytes) {
  return bytes < list_pool().min_bytes ? allocate_scratch(bytes) : take(list_pool(), bytes, true);
}
void release_large(void* pointer, std::size_t) noexcept {
  if (pointer && malloc_usable_size(pointer) < list_pool().min_bytes) return release_scratch(pointer);
  give(list_pool(), pointer);
}
void* allocate_scratch(std::size_t bytes) { return take(scratch_pool(), bytes, false); }
void release_scratch(void* pointer) noexcept { give(scratch_pool(), pointer); }

BlockReleaseHook set_block_release_hook(BlockReleaseHook hook) { return release_hook.exchange(hook); }

std::size_t cached_buffer_bytes() { return held_bytes(list_pool()) + held_bytes(scratch_pool()); }

}  // namespace horizon::detail

namespace horizon {

void release_cached_buffers() {
  detail::empty(detail::list_pool());
  detail::empty(detail::scratch_pool());
}

}  // namespace horizon
