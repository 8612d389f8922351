#pragma once
// Where each chunk of work writes its output when threads take the chunks in order and the
// sizes are known only once a chunk is done: a single-pass prefix by decoupled look-back (as
// GPU scans do). A chunk publishes its size, then sums the sizes of the chunks before it back
// to the first one that has published its own place, so it waits only for chunks that are
// still counting, never for chunks that are writing.
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>

namespace horizon::detail {

class ChunkPrefix {
 public:
  explicit ChunkPrefix(std::int64_t chunks) : state_(new std::atomic<std::uint64_t>[static_cast<std::size_t>(chunks)]()) {}

  /// The next chunk to work on, in order (0, 1, 2, ...) across all threads.
  std::int64_t take() { return next_.fetch_add(1, std::memory_order_relaxed); }

  /// Publishes the size of chunk `c` (taken by this thread) and returns the sum of the sizes of
  /// chunks 0 .. c - 1: where its output starts. Never blocks on work other than counting: a
  /// chunk before `c` was taken earlier and publishes its size before it looks back.
  std::int64_t place(std::int64_t c, std::int64_t size) {
    state_[c].store(static_cast<std::uint64_t>(size) | counted, std::memory_order_release);
    std::int64_t before = 0;
    for (std::int64_t p = c - 1; p >= 0; --p) {
      const std::uint64_t state = published(p);
      before += static_cast<std::int64_t>(state & value);
      if (state & placed) break;  // its value is the sum up to and including it
    }
    state_[c].store(static_cast<std::uint64_t>(before + size) | placed, std::memory_order_release);
    return before;
  }

 private:
  static constexpr std::uint64_t counted = std::uint64_t{1} << 62, placed = std::uint64_t{1} << 63, value = counted - 1;

  std::uint64_t published(std::int64_t p) const {
    for (int spins = 0;; ++spins) {
      const std::uint64_t state = state_[p].load(std::memory_order_acquire);
      if (state) return state;
      if (spins >= 64) std::this_thread::yield();  // more threads than cores: let the counting one run
    }
  }

  std::unique_ptr<std::atomic<std::uint64_t>[]> state_;
  std::atomic<std::int64_t> next_{0};
};

}  // namespace horizon::detail
