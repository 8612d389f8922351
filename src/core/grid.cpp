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

namespace {

/// The bounding box of n points of D coordinates of type T (z = 0 in 2-D): typed, so the loop
/// compiles without a branch on the type per coordinate.
template <class T, int D>
Bounds bounds_of(const T* xyz, std::int64_t n, int threads) {
  auto at = [xyz](std::int64_t i, int a) { return a < D ? static_cast<double>(xyz[i * D + a]) : 0.0; };
  double lx = at(0, 0), ly = at(0, 1), lz = at(0, 2);
  double hx = lx, hy = ly, hz = lz;
  auto extend = [at](std::int64_t i, double& lx, double& ly, double& lz, double& hx, double& hy, double& hz) {
    const double x = at(i, 0), y = at(i, 1), z = at(i, 2);
    lx = std::min(lx, x), ly = std::min(ly, y), lz = std::min(lz, z);
    hx = std::max(hx, x), hy = std::max(hy, y), hz = std::max(hz, z);
  };
  if (threads <= 1) {  // no parallel region (parallel_for.hpp says why)
    for (std::int64_t i = 0; i < n; ++i) extend(i, lx, ly, lz, hx, hy, hz);
  } else {
#pragma omp parallel for num_threads(threads) reduction(min : lx, ly, lz) reduction(max : hx, hy, hz)
    for (std::int64_t i = 0; i < n; ++i) extend(i, lx, ly, lz, hx, hy, hz);
  }
  Bounds box;
  box.lo = {lx, ly, lz};
  box.hi = {hx, hy, hz};
  return box;
}

}  // namespace

Bounds bounds_of(PointView points, int threads) {
  if (points.empty()) return Bounds{};
  const auto n = static_cast<std::int64_t>(points.size());
  const bool flat = points.dims() == 2;
  if (points.is_float32()) {
    const float* xyz = points.float32_data();
    return flat ? bounds_of<float, 2>(xyz, n, threads) : bounds_of<float, 3>(xyz, n, threads);
  }
  const double* xyz = points.float64_data();
  return flat ? bounds_of<double, 2>(xyz, n, threads) : bounds_of<double, 3>(xyz, n, threads);
}

Bounds bounds_of(PointView points, PointView more, int threads) {
  if (points.empty()) return bounds_of(more, threads);
  Bounds box = bounds_of(points, threads);
  if (!more.empty()) {
    const Bounds other = bounds_of(more, threads);
    for (std::size_t a = 0; a < 3; ++a) {
      box.lo[a] = std::min(box.lo[a], other.lo[a]);
      box.hi[a] = std::max(box.hi[a], other.hi[a]);
    }
  }
  return box;
}

Grid Grid::fit(PointView points, PointView more, double horizon, int cells_per_horizon, int threads) {
  if (more.empty()) return fit(points, horizon, cells_per_horizon, threads);
  return from_bounds(bounds_of(points, more, threads), points.dims(), points.size() + more.size(), horizon,
                     cells_per_horizon);
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

  // (x - origin) * (1 / side) carries three roundings, an error below 2^-51 of extent/side
  // cells per point; widening the side by 2^-49 of the extent keeps every pair closer than the
  // horizon within k cells along each axis, however far the points lie from the origin.
  const int k = cells_per_horizon;
  g.cell_side = (horizon + std::ldexp(extent, -49)) / k;
  g.inverse_side = 1.0 / g.cell_side;
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
