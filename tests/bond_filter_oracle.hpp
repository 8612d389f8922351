#pragma once
// Bond filters' test oracle: a brute-force pass over a list's pairs with `cuts`, random shapes,
// and a lattice whose points lie on shapes' edges, rims and planes.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "horizon/bond_filter.hpp"
#include "horizon/generate.hpp"

namespace horizon {

// The rows of `list` without the bonds any filter cuts, pair by pair (a: the smaller id's end).
inline NeighborList brute_force_filter(const NeighborList& list, const PointSet& points, const std::vector<BondFilter>& filters) {
  Buffer<std::int64_t> offsets{0};
  Buffer<point_id> indices;
  for (std::size_t i = 0; i < list.size(); ++i) {
    for (point_id j : list.row(i)) {
      std::array<double, 3> a{}, b{};
      const std::size_t lo = std::min<std::size_t>(i, j), hi = std::max<std::size_t>(i, j);
      for (int d = 0; d < points.dims; ++d) {
        a[d] = points.xyz[lo * points.dims + d];
        b[d] = points.xyz[hi * points.dims + d];
      }
      bool kept = true;
      for (const BondFilter& f : filters) kept = kept && !cuts(f, a.data(), b.data());
      if (kept) indices.push_back(j);
    }
    offsets.push_back(static_cast<std::int64_t>(indices.size()));
  }
  return NeighborList(std::move(offsets), std::move(indices), list.is_half());
}

// In 2-D the shapes stand across the plane z = 0 (normal in it, bottom along z).
inline std::vector<BondFilter> random_filters(std::mt19937_64& rng, int count, int dims) {
  std::uniform_real_distribution<double> unit(-1, 1), place(2, 8), size(1, 5);
  std::vector<BondFilter> filters;
  for (int f = 0; f < count; ++f) {
    std::array<double, 3> n{unit(rng), unit(rng), dims == 3 ? unit(rng) : 0.0};
    std::array<double, 3> t = dims == 3 ? std::array<double, 3>{unit(rng), unit(rng), unit(rng)} : std::array<double, 3>{0, 0, 1};
    auto normalise = [](std::array<double, 3>& v) {
      const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (double& x : v) x /= l;
    };
    normalise(n);
    const double along = n[0] * t[0] + n[1] * t[1] + n[2] * t[2];
    for (int a = 0; a < 3; ++a) t[a] -= along * n[a];  // perpendicular to n
    normalise(t);
    const std::array<double, 3> at{place(rng), place(rng), dims == 3 ? place(rng) : -1.0};
    if (f % 2) filters.push_back(DiskFilter{at, n, size(rng)});
    else filters.push_back(RectangleFilter{n, at, t, size(rng), size(rng)});
  }
  return filters;
}

// The integers 0..7 on each axis (plus `offset`) and shapes through them: bonds through the
// edges (inside), the rim (outside) and lying in a plane, and ends on a plane.
struct ShapesOnLattice {
  PointSet points;
  std::vector<BondFilter> filters;
};

inline ShapesOnLattice shapes_on_lattice(double offset) {
  PointSet points = lattice(8, 3, 8.0);
  for (double& x : points.xyz) x += offset - 0.5;
  const double o = offset;
  return {std::move(points),
          {RectangleFilter{{1, 0, 0}, {o + 2, o + 1, o + 5}, {0, 1, 0}, 4, 3},   // x = 2: y in [1, 5], z in [2, 5]
           RectangleFilter{{0, 0, 1}, {o + 1, o + 1, o + 4.5}, {1, 0, 0}, 5, 5},  // z = 4.5: its edges on the lattice
           DiskFilter{{o + 5.5, o + 3, o + 3}, {1, 0, 0}, 2}}};                   // x = 5.5, rim through lattice points
}

}  // namespace horizon
