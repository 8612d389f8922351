#pragma once
// The benchmarks' medians: of a set of timings, and of `reps` runs of a callable, in seconds.
#include <algorithm>
#include <utility>
#include <vector>

#include "horizon/stopwatch.hpp"

inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

template <class F>
double median_seconds(int reps, F once) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    horizon::Stopwatch clock;
    once();
    t.push_back(clock.lap());
  }
  return median(std::move(t));
}
