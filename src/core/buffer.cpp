#include "horizon/buffer.hpp"

#include <algorithm>
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
// Freed blocks of at least `cached_min` bytes (a search's offsets and indices) are kept and
// handed to the next requests they fit: a solver that searches every step (free the old list,
// build the new one) otherwise faults in every page of every list again, which costs as much as
// copying the list out of a GPU (H200 host: 16 GB in 0.30-0.75 s against the 0.31 s PCIe
// copy). Large blocks are taken 1/16 larger than asked (address space only: untouched pages
// cost nothing) so that the next step's list, a little longer, still fits.
namespace {

// 32 MB: glibc maps larger blocks afresh at every malloc (its mmap threshold stops there).
constexpr std::size_t cached_min = std::size_t{32} << 20;
constexpr int slots = 2;

struct Block {
  void* pointer = nullptr;
  std::size_t bytes = 0;
};

struct Cache {
  std::mutex mutex;
  Block block[slots];
};

Cache& cache() {
  static auto* c = new Cache;  // never destroyed: lists may be freed by static destructors
  return *c;
}

/// At most a quarter of the machine's memory is held back.
std::size_t most_cached() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(page) / 4 : 0;
}

void free_all(Block (&blocks)[slots]) {
  for (Block& b : blocks) std::free(b.pointer);
}

}  // namespace

void* allocate_scratch(std::size_t bytes) {
  void* p = std::malloc(bytes ? bytes : 1);
  if (!p) throw std::bad_alloc();
  if (bytes >= cached_min) advise_huge_pages(p, bytes);
  return p;
}

void* allocate_large(std::size_t bytes) {
  if (bytes < cached_min) return allocate_scratch(bytes);
  Cache& c = cache();
  Block stale[slots];
  {
    std::lock_guard lock(c.mutex);
    Block* fit = nullptr;  // the smallest block that holds `bytes` and is at most twice as large
    for (Block& b : c.block)
      if (b.pointer && b.bytes >= bytes && b.bytes / 2 <= bytes && (!fit || b.bytes < fit->bytes)) fit = &b;
    if (fit) return std::exchange(*fit, Block{}).pointer;
    std::swap(stale, c.block);  // none fits: give their memory back before taking more
  }
  free_all(stale);
  constexpr std::size_t align = std::size_t{2} << 20;
  const std::size_t padded = (bytes + bytes / 16 + align - 1) / align * align;
  return allocate_scratch(padded);
}

void release_large(void* pointer, std::size_t bytes) noexcept {
  if (pointer) bytes = malloc_usable_size(pointer);  // a padded or reused block is larger than asked
  if (!pointer || bytes < cached_min) return std::free(pointer);
  Cache& c = cache();
  {
    std::lock_guard lock(c.mutex);
    std::size_t held = 0;
    Block* smallest = &c.block[0];
    for (Block& b : c.block) {
      held += b.bytes;
      if (b.bytes < smallest->bytes) smallest = &b;
    }
    // Keep the new block in place of the smallest one, if it is larger and within the limit.
    if (bytes > smallest->bytes && held - smallest->bytes + bytes <= most_cached())
      pointer = std::exchange(*smallest, Block{pointer, bytes}).pointer;
  }
  std::free(pointer);
}

std::size_t cached_buffer_bytes() {
  Cache& c = cache();
  std::lock_guard lock(c.mutex);
  std::size_t held = 0;
  for (const Block& b : c.block) held += b.bytes;
  return held;
}

}  // namespace horizon::detail

namespace horizon {

void release_cached_buffers() {
  detail::Cache& c = detail::cache();
  detail::Block stale[detail::slots];
  {
    std::lock_guard lock(c.mutex);
    std::swap(stale, c.block);
  }
  detail::free_all(stale);
}

}  // namespace horizon
