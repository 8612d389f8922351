#pragma once
/// \file metric.hpp
/// The pair criterion every backend shares: metric distance strictly less than the horizon.
/// Euclidean compares ((dx*dx + dy*dy) + dz*dz) with horizon^2; Manhattan and Chebyshev compare
/// the sum or maximum of |d| with the horizon. Compiled without FMA contraction, so the CPU and
/// GPU backends take identical decisions on every pair.
#include <math.h>

#include <cmath>
#include <string>

// Functions the CUDA kernels share with the CPU backends.
#if defined(__CUDACC__)
#define HORIZON_HOST_DEVICE __host__ __device__
#else
#define HORIZON_HOST_DEVICE
#endif

namespace horizon {

enum class Metric { euclidean, manhattan, chebyshev };

/// "l2", "l1", "linf" (the CLI spelling) and back.
Metric parse_metric(const std::string& name);
const char* metric_name(Metric metric);

/// The value a metric's accumulated distance is compared with: horizon^2 for Euclidean.
inline double metric_threshold(Metric metric, double horizon) {
  return metric == Metric::euclidean ? horizon * horizon : horizon;
}

/// Accumulated distance of a pair with coordinate differences dx, dy, dz (dz = 0 in 2-D).
/// Pairs are neighbours when this is < metric_threshold().
template <Metric M>
HORIZON_HOST_DEVICE inline double metric_accumulate(double dx, double dy, double dz) {
  if constexpr (M == Metric::euclidean) {
    return (dx * dx + dy * dy) + dz * dz;
  } else if constexpr (M == Metric::manhattan) {
    return (fabs(dx) + fabs(dy)) + fabs(dz);
  } else {
    return fmax(fmax(fabs(dx), fabs(dy)), fabs(dz));
  }
}

}  // namespace horizon
