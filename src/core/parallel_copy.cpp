#include "parallel_copy.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include <omp.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace horizon::detail {

namespace {

constexpr std::size_t huge_page = std::size_t{2} << 20;
thread_local int bounded_threads = 0;  // 0: no CopyThreads on this thread

}  // namespace

int copy_threads() { return bounded_threads > 0 ? bounded_threads : omp_get_max_threads(); }
CopyThreads::CopyThreads(int threads) : saved_(bounded_threads) { bounded_threads = threads > 0 ? threads : saved_; }
CopyThreads::~CopyThreads() { bounded_threads = saved_; }

void stream_copy(void* destination, const void* source, std::size_t bytes) {
  auto* to = static_cast<char*>(destination);
  const auto* from = static_cast<const char*>(source);
#if defined(__SSE2__)
  const std::size_t head = std::min(bytes, (16 - reinterpret_cast<std::uintptr_t>(to) % 16) % 16);
  std::memcpy(to, from, head);
  std::size_t at = head;
  for (; at + 64 <= bytes; at += 64) {
    const auto* s = reinterpret_cast<const __m128i*>(from + at);
    auto* d = reinterpret_cast<__m128i*>(to + at);
    const __m128i a = _mm_loadu_si128(s), b = _mm_loadu_si128(s + 1), c = _mm_loadu_si128(s + 2),
                  e = _mm_loadu_si128(s + 3);
    _mm_stream_si128(d, a);
    _mm_stream_si128(d + 1, b);
    _mm_stream_si128(d + 2, c);
    _mm_stream_si128(d + 3, e);
  }
  std::memcpy(to + at, from + at, bytes - at);
  _mm_sfence();  // the streamed stores are visible before this thread leaves the loop
#else
  std::memcpy(to, from, bytes);
#endif
}

void parallel_copy(void* to, const void* from, std::size_t bytes) {
  auto* dest = static_cast<char*>(to);
  const auto* src = static_cast<const char*>(from);
  // Pieces of 2 MB, each ending at a 2 MB boundary of the destination, when there are enough for
  // every core; a smaller copy (the chunks at either end of a staged transfer) is cut into one
  // piece per core instead of leaving most of them idle.
  const int team = copy_threads();
  const auto threads = static_cast<std::size_t>(team);
  constexpr std::size_t page = 4096, smallest = 16 * page;
  const std::size_t piece =
      bytes >= threads * huge_page ? huge_page : std::max(smallest, (bytes / threads + page - 1) / page * page);
  // Piece i ends at the (i + 1)-th multiple of `piece` in the address space past the start.
  const std::size_t lead = piece - reinterpret_cast<std::uintptr_t>(dest) % piece;
  const auto pieces = static_cast<std::int64_t>(bytes <= lead ? 1 : 1 + (bytes - lead + piece - 1) / piece);
#pragma omp parallel for schedule(static) num_threads(team) if (pieces > 2 && team > 1)
  for (std::int64_t i = 0; i < pieces; ++i) {
    const std::size_t begin = i == 0 ? 0 : lead + static_cast<std::size_t>(i - 1) * piece;
    const std::size_t end = std::min(bytes, lead + static_cast<std::size_t>(i) * piece);
    stream_copy(dest + begin, src + begin, end - begin);
  }
}

void parallel_copy_coordinates(double* to, PointView points, std::size_t first, std::size_t count) {
  if (!points.is_float32()) {
    parallel_copy(to, points.float64_data() + first, count * sizeof(double));
    return;
  }
  const auto dims = static_cast<std::size_t>(points.dims());
  const auto n = static_cast<std::int64_t>(count);
  const int team = copy_threads();
#pragma omp parallel for schedule(static) num_threads(team) if (n > (1 << 16) && team > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const std::size_t at = first + static_cast<std::size_t>(i);
    to[i] = points(at / dims, static_cast<int>(at % dims));
  }
}

void parallel_touch(void* at, std::size_t bytes) {
  constexpr std::size_t page = 4096;
  const auto pages = static_cast<std::int64_t>((bytes + page - 1) / page);
  char* base = static_cast<char*>(at);
  const int team = copy_threads();
#pragma omp parallel for schedule(static) num_threads(team) if (pages > 256 && team > 1)
  for (std::int64_t i = 0; i < pages; ++i) base[static_cast<std::size_t>(i) * page] = 0;
}

void advise_huge_pages(void* at, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const auto begin = (reinterpret_cast<std::uintptr_t>(at) + huge_page - 1) / huge_page * huge_page;
  const auto end = (reinterpret_cast<std::uintptr_t>(at) + bytes) / huge_page * huge_page;
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint: errors ignored
#else
  (void)at;
  (void)bytes;
#endif
}

}  // namespace horizon::detail
