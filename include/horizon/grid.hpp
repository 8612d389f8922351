#pragma once
/// \file grid.hpp
/// The fixed grid of the thesis (§4.2): cubic cells of side about horizon/k laid over the
/// bounding box, padded by k empty cells on every side so that a stencil of k cells in each
/// direction never leaves the grid.
#include <array>
#include <cmath>
#include <cstdint>

#include "horizon/points.hpp"

namespace horizon {

/// The bounding box of a point set (z = 0 in 2-D).
struct Bounds {
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
};
Bounds bounds_of(PointView points, int threads = 1);
/// The bounding box of two point sets together (an empty one adds nothing).
Bounds bounds_of(PointView points, PointView more, int threads = 1);

struct Grid {
  int dims = 3;
  int cells_per_horizon = 1;  ///< k: the stencil reaches k cells each way
  double horizon = 0;         ///< the largest horizon the grid serves
  double cell_side = 0;       ///< >= horizon / k (see fit())
  double inverse_side = 0;    ///< 1 / cell_side: a cell coordinate is a product, not a division
  std::array<double, 3> origin{};       ///< lower corner of the bounding box
  std::array<std::int64_t, 3> cells{};  ///< cells along each axis, padding included (1 for z in 2-D)
  bool dense = true;  ///< a table with one entry per cell is O(N): index cells by linear id

  /// The grid for `points` with cells of side horizon/k. The side is enlarged by the rounding
  /// error of computing cell coordinates (2^-49 of the extent, nothing at ordinary extents), so
  /// two points closer than the horizon are never more than k cells apart along any axis.
  static Grid fit(PointView points, double horizon, int cells_per_horizon, int threads = 1) {
    return from_bounds(bounds_of(points, threads), points.dims(), points.size(), horizon,
                       cells_per_horizon);
  }
  /// The grid over two point sets (points and their periodic images).
  static Grid fit(PointView points, PointView more, double horizon, int cells_per_horizon, int threads = 1);
  /// The same grid from the bounding box of `count` points (the GPU reduces the box itself).
  static Grid from_bounds(const Bounds& box, int dims, std::size_t count, double horizon,
                          int cells_per_horizon);

  /// Cell coordinate along `axis` of a point with coordinate x (padding included).
  std::int64_t cell_of(double x, int axis) const {
    // floor by truncation and a correction: std::floor is a library call in a portable x86 build
    const double t = (x - origin[axis]) * inverse_side;
    const auto truncated = static_cast<std::int64_t>(t);
    return truncated - (t < static_cast<double>(truncated)) + cells_per_horizon;
  }
  /// Number of cells in the grid (as a double: it may not fit any integer when sparse).
  double cell_count() const {
    return static_cast<double>(cells[0]) * static_cast<double>(cells[1]) *
           static_cast<double>(cells[2]);
  }
  /// Linear id of a cell, x fastest (thesis eq. 4.2.1); only meaningful when dense.
  std::int64_t linear_id(std::int64_t cx, std::int64_t cy, std::int64_t cz) const {
    return cx + cells[0] * (cy + cells[1] * cz);
  }
};

/// Throws horizon::Error unless the horizon is finite and > 0 and k is 1, 2 or 3.
void validate_horizon(double horizon, int cells_per_horizon);

}  // namespace horizon
