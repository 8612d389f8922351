#include "horizon/grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "horizon/error.hpp"

namespace horizon {

void validate_horizon(double horizon, int cells_per_horizon) {
  if (!(std::isfinite(horizon) && horizon > 0))
    throw Error("horizon must be finite and > 0, got " + std::to_string(horizon));
  if (cells_per_horizon < 1 || cells_per_horizon > 3)
    throw Error("cells per horizon must be 1, 2 or 3, got " + std::to_string(cells_per_horizon));
}

Bounds bounds_of(PointView points) {
  Bounds box;
  if (points.empty()) return box;
  for (int a = 0; a < points.dims(); ++a) box.lo[a] = box.hi[a] = points(0, a);
  for (std::size_t i = 1; i < points.size(); ++i)
    for (int a = 0; a < points.dims(); ++a) {
      box.lo[a] = std::min(box.lo[a], points(i, a));
      box.hi[a] = std::max(box.hi[a], points(i, a));
    }
  return box;
}

Grid Grid::from_bounds(const Bounds& box, int dims, std::size_t count, double horizon,
                       int cells_per_horizon) {
  validate_horizon(horizon, cells_per_horizon);
  Grid g;
  g.dims = dims;
  g.cells_per_horizon = cells_per_horizon;
  g.horizon = horizon;
  const auto& lo = box.lo;
  const auto& hi = box.hi;
  double extent = 0;
  for (int a = 0; a < g.dims; ++a) extent = std::max(extent, hi[a] - lo[a]);
  if (!std::isfinite(extent)) throw Error("the extent of the points overflows a double");

  // (x - origin) / side carries a rounding error below 2^-52 of extent/side cells per point;
  // widening the side by 2^-49 of the extent keeps every pair closer than the horizon within
  // k cells along each axis, however far the points lie from the origin.
  const int k = cells_per_horizon;
  g.cell_side = (horizon + std::ldexp(extent, -49)) / k;
  g.origin = lo;
  for (int a = 0; a < 3; ++a) {
    if (a >= g.dims) {
      g.cells[a] = 1;
      continue;
    }
    const double along = std::floor((hi[a] - lo[a]) / g.cell_side);
    g.cells[a] = static_cast<std::int64_t>(along) + 1 + 2 * k;
  }
  // Index cells by linear id when a table over all cells stays O(N); else look them up sparsely.
  const double budget = 16.0 * static_cast<double>(count) + 1048576.0;
  g.dense = g.cell_count() <= budget;
  return g;
}

}  // namespace horizon
