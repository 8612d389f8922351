#pragma once
// What read_points promises for any file it accepts.
#include <cmath>

#include "fuzz_input.hpp"
#include "horizon/points.hpp"

namespace horizon::fuzz {

inline void check_points(const PointSet& points) {
  require(points.dims == 2 || points.dims == 3, "dims is 2 or 3");
  require(points.xyz.size() % static_cast<std::size_t>(points.dims) == 0, "whole points");
  for (double x : points.xyz) require(std::isfinite(x), "finite coordinates");
}

}  // namespace horizon::fuzz
