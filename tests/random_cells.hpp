#pragma once
// Random periodic cells and points in and around them, for the cell search's tests on one node
// and across ranks.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "horizon/cell.hpp"
#include "horizon/points.hpp"

namespace horizon::testing {

/// A random right-handed cell: each vector of length 1-3, at least `min_angle` radians from the
/// plane of the other two (small: nearly degenerate), possibly rotated; random pbc.
inline Cell random_cell(std::mt19937_64& rng, int dims, double min_angle) {
  std::uniform_real_distribution<double> unit(-1, 1), length(1, 3);
  for (;;) {
    Cell cell;
    for (int k = 0; k < dims; ++k) {
      double norm = 0;
      for (int a = 0; a < dims; ++a) norm += (cell.vectors[k][a] = unit(rng)) * cell.vectors[k][a];
      const double scale = length(rng) / std::sqrt(norm);
      for (int a = 0; a < dims; ++a) cell.vectors[k][a] *= scale;
      cell.pbc[k] = rng() % 4 != 0;
    }
    if (dims == 2) cell.vectors[2][2] = 1;
    const auto& v = cell.vectors;
    const double cx = v[1][1] * v[2][2] - v[1][2] * v[2][1], cy = v[1][2] * v[2][0] - v[1][0] * v[2][2],
                 cz = v[1][0] * v[2][1] - v[1][1] * v[2][0];
    const double det = v[0][0] * cx + v[0][1] * cy + v[0][2] * cz;
    if (det < 0) std::swap(cell.vectors[0], cell.vectors[1]);  // right-handed
    // The angle between each vector and the other two's plane: sin = |det| / (|a| |b x c|).
    bool flat_enough = std::fabs(det) > 0;
    for (int k = 0; k < dims && flat_enough; ++k) {
      const auto& a = v[k];
      const auto& b = v[(k + 1) % 3];
      const auto& c = v[(k + 2) % 3];
      const double n[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
      const double sine = std::fabs(det) / (std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) *
                                            std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
      flat_enough = std::asin(std::min(1.0, sine)) >= min_angle;
    }
    if (flat_enough) return cell;
  }
}

/// Points inside and around the cell (up to two cells out), some coincident.
inline PointSet points_around(const Cell& cell, int dims, std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> fraction(-2, 3);
  PointSet points(dims, {});
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && rng() % 10 == 0) {  // a copy of the last point
      for (int a = 0; a < dims; ++a) points.xyz.push_back(points.xyz[(i - 1) * dims + a]);
      continue;
    }
    double f[3];
    for (int k = 0; k < dims; ++k) f[k] = fraction(rng);
    for (int a = 0; a < dims; ++a) {
      double x = 0;
      for (int k = 0; k < dims; ++k) x += f[k] * cell.vectors[k][a];
      points.xyz.push_back(x);
    }
  }
  return points;
}

}  // namespace horizon::testing
