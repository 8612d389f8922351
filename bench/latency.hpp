#pragma once
// horizon_bench --latency: what one call costs a solver that searches every step, at sizes from
// tens to 10^5 points, per backend and for the default, idle and with busy processes beside it.
#include <vector>

namespace bench {

struct LatencyOptions {
  std::vector<int> sizes{10, 100, 1000, 10000, 100000};
  std::vector<int> busy{0, -1};  ///< busy processes started beside the calls (-1: one per hardware thread)
  double neighbours = 30;        ///< mean neighbours per point (the cloud's density)
  double seconds = 1.0;          ///< time spent per size, backend and load (at least 11 calls)
  int block = 1;                 ///< calls of one backend in a row before the next one's
};

/// Prints CSV: busy, points, backend, threads, calls, median_us, p99_us, max_us, first_us. The
/// anchors, on one core: the textbook cell list (bench/textbook_cell_list.cpp) and, when the
/// benchmarks were built with a copy of it, vesin (its full list, unsorted, reused call to call).
int run_latency(const LatencyOptions& options);

}  // namespace bench
