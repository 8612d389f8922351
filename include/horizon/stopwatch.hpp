#pragma once
/// \file stopwatch.hpp
/// Wall-clock seconds since construction or the last lap, for per-phase timings.
#include <chrono>

namespace horizon {

class Stopwatch {
public:
  /// Seconds since construction or the previous lap(); starts the next lap.
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return seconds;
  }

private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace horizon
