#pragma once
// The benchmarks' timer: the median of `reps` runs of a callable, in seconds.
#include <algorithm>
#include <vector>

#include "horizon/stopwatch.hpp"

template <class F>
double median_seconds(int reps, F once) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    horizon::Stopwatch clock;
    once();
    t.push_back(clock.lap());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}
