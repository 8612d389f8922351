#include "horizon/bond_filter.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <omp.h>

#include "select_entries.hpp"
#include "horizon/error.hpp"

namespace horizon {

namespace {

using Vec = std::array<double, 3>;

Vec minus(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec& a, const Vec& b) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

const Vec& plane_origin(const BondFilter& f) {
  return std::holds_alternative<RectangleFilter>(f) ? std::get<RectangleFilter>(f).lower_left_corner
                                                    : std::get<DiskFilter>(f).center;
}
const Vec& plane_normal(const BondFilter& f) {
  return std::holds_alternative<RectangleFilter>(f) ? std::get<RectangleFilter>(f).normal
                                                    : std::get<DiskFilter>(f).normal;
}

/// Where the bond a-b meets the filter's plane (the header's convention), if it does.
std::optional<Vec> meets_plane(const BondFilter& f, const Vec& a, const Vec& b) {
  const double sa = dot(minus(a, plane_origin(f)), plane_normal(f));
  const double sb = dot(minus(b, plane_origin(f)), plane_normal(f));
  if ((sa > 0 && sb > 0) || (sa < 0 && sb < 0) || (sa == 0 && sb == 0)) return std::nullopt;
  const double t = sa / (sa - sb);
  return Vec{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

/// x's coordinates along the rectangle's bottom and side, from its lower left corner.
std::pair<double, double> rectangle_coordinates(const RectangleFilter& f, const Vec& x) {
  const Vec r = minus(x, f.lower_left_corner);
  return {dot(r, f.bottom_unit_vector), dot(r, cross(f.bottom_unit_vector, f.normal))};
}

bool inside(const RectangleFilter& f, const Vec& x) {
  const auto [along_bottom, along_side] = rectangle_coordinates(f, x);
  return along_bottom >= 0 && along_bottom <= f.bottom_length && along_side >= 0 && along_side <= f.side_length;
}

bool inside(const DiskFilter& f, const Vec& x) {
  const Vec r = minus(x, f.center);
  return dot(r, r) < f.radius * f.radius;
}

Vec point(PointView p, std::size_t i) { return {p(i, 0), p(i, 1), p.dims() == 3 ? p(i, 2) : 0.0}; }

/// Per point, which filters' planes it lies strictly above and below (bit f), and which it is
/// near: within `reach` of the plane and of the shape's extent. A bond can only cross filter f
/// when its ends are not both above nor both below, and, when no longer than `reach`, only when
/// both are near f (so rows of points near no filter are kept whole). One struct per point: a
/// bond's test reads its other end's three masks from one cache line.
struct Sides {
  std::uint64_t above = 0, below = 0, near = 0;
};

bool within_reach(const BondFilter& f, const Vec& x, double side, double reach) {
  if (!(std::abs(side) < reach)) return false;
  if (const auto* r = std::get_if<RectangleFilter>(&f)) {
    const auto [along_bottom, along_side] = rectangle_coordinates(*r, x);
    return along_bottom > -reach && along_bottom < r->bottom_length + reach && along_side > -reach &&
           along_side < r->side_length + reach;
  }
  const DiskFilter& disk = std::get<DiskFilter>(f);
  const Vec d = minus(x, disk.center);
  return dot(d, d) < (disk.radius + reach) * (disk.radius + reach);
}

std::vector<Sides> sides_of(PointView points, const std::vector<BondFilter>& filters, double reach, int threads) {
  const auto n = static_cast<std::int64_t>(points.size());
  std::vector<Sides> sides(points.size());
  // A margin for the rounding of the dot products (bond lengths and offsets are O(reach) here).
  const double padded = reach > 0 ? reach * (1 + 1e-6) : std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec x = point(points, static_cast<std::size_t>(i));
    Sides& s = sides[static_cast<std::size_t>(i)];
    for (std::size_t f = 0; f < filters.size(); ++f) {
      const double side = dot(minus(x, plane_origin(filters[f])), plane_normal(filters[f]));
      s.above |= std::uint64_t{side > 0} << f;
      s.below |= std::uint64_t{side < 0} << f;
      s.near |= std::uint64_t{within_reach(filters[f], x, side, padded)} << f;
    }
  }
  return sides;
}

}  // namespace

bool cuts(const BondFilter& filter, const double* a, const double* b) {
  const std::optional<Vec> x = meets_plane(filter, {a[0], a[1], a[2]}, {b[0], b[1], b[2]});
  return x && std::visit([&](const auto& shape) { return inside(shape, *x); }, filter);
}

namespace {

/// one_set: `columns` is `rows` (ids and rows index one point set).
NeighborList filter(NeighborList list, PointView rows, PointView columns, bool one_set,
                    const std::vector<BondFilter>& filters, double reach, int threads) {
  if (threads <= 0) threads = omp_get_max_threads();
  if (filters.size() > max_bond_filters)
    throw Error(std::to_string(filters.size()) + " bond filters: at most " + std::to_string(max_bond_filters) +
                " are applied at once");
  if (list.size() != rows.size())
    throw Error("bond filters: the list has " + std::to_string(list.size()) + " rows for " +
                std::to_string(rows.size()) + " points");
  if (!(reach >= 0)) throw Error("bond filters: the reach must be >= 0 (0: unknown)");
  const std::vector<Sides> row_sides = sides_of(rows, filters, reach, threads);
  const std::vector<Sides> column_sides = one_set ? std::vector<Sides>{} : sides_of(columns, filters, reach, threads);
  const Sides* col = one_set ? row_sides.data() : column_sides.data();

  const std::uint64_t all = filters.size() == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << filters.size()) - 1;
  // Whether the bond i-j survives every filter whose plane it may cross.
  auto kept = [&](std::size_t i, point_id j) {
    const Sides &at_i = row_sides[i], &at_j = col[j];
    const std::uint64_t same_side = (at_i.above & at_j.above) | (at_i.below & at_j.below);
    std::uint64_t candidates = ~same_side & at_i.near & at_j.near & all;
    if (!candidates) return true;
    Vec a = point(rows, i), b = point(columns, static_cast<std::size_t>(j));
    if (one_set && static_cast<std::size_t>(j) < i) std::swap(a, b);  // a: the smaller id's end
    for (; candidates; candidates &= candidates - 1)
      if (cuts(filters[static_cast<std::size_t>(std::countr_zero(candidates))], a.data(), b.data())) return false;
    return true;
  };

  // Rows of points near no filter (with a known reach) need no tests.
  return detail::select_entries(std::move(list), [&](std::size_t i) { return row_sides[i].near == 0; }, kept, threads);
}

}  // namespace

NeighborList filter_bonds(NeighborList list, PointView rows, PointView columns,
                          const std::vector<BondFilter>& filters, double reach, int threads) {
  return filter(std::move(list), rows, columns, false, filters, reach, threads);
}

NeighborList filter_bonds(NeighborList list, PointView points, const std::vector<BondFilter>& filters,
                          double reach, int threads) {
  return filter(std::move(list), points, points, true, filters, reach, threads);
}

}  // namespace horizon
