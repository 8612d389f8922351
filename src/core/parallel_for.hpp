#pragma once
// f(i) for every i of [0, n) on a team of `threads` OpenMP threads, or on the calling thread
// alone without entering a parallel region when the team would be one thread: libgomp enters
// even an inactive region (`if (false)`) through a team of one and a futex wake, ~0.4 us each,
// and a 100-point search on one core passed a dozen (a third of its 12 us, 2-core Zen 4 VM).
#include <cstdint>

namespace horizon::detail {

/// Iterations shared out in equal blocks (OpenMP's schedule(static)).
template <class F>
void parallel_for(std::int64_t n, int threads, F&& f) {
  if (threads <= 1) {
    for (std::int64_t i = 0; i < n; ++i) f(i);
    return;
  }
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t i = 0; i < n; ++i) f(i);
}

/// Iterations handed out `chunk` at a time to whichever thread is free (schedule(dynamic)): for
/// work items of uneven cost, such as runs of cells.
template <class F>
void parallel_for_dynamic(std::int64_t n, int threads, F&& f, int chunk = 1) {
  if (threads <= 1) {
    for (std::int64_t i = 0; i < n; ++i) f(i);
    return;
  }
#pragma omp parallel for schedule(dynamic, chunk) num_threads(threads)
  for (std::int64_t i = 0; i < n; ++i) f(i);
}

}  // namespace horizon::detail
