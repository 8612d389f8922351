#include "horizon/bond_filter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <omp.h>

#include "select_entries.hpp"
#include "horizon/error.hpp"
#include "horizon/grid.hpp"

namespace horizon {

namespace {

using Vec = std::array<double, 3>;

Vec minus(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec& a, const Vec& b) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// A filter with what each test needs worked out once: its plane, and for a rectangle the
/// direction of its side (bottom x normal). Every test below computes in the same order as
/// before this was cached, so results are bit for bit those of the header's convention.
struct Shape {
  bool disk = false;
  Vec origin{}, normal{}, bottom{}, side{};  ///< origin: the rectangle's corner or the disk's centre
  double bottom_length = 0, side_length = 0, radius = 0;
};

Shape shape_of(const BondFilter& f) {
  Shape s;
  if (const auto* r = std::get_if<RectangleFilter>(&f)) {
    s.origin = r->lower_left_corner;
    s.normal = r->normal;
    s.bottom = r->bottom_unit_vector;
    s.side = cross(r->bottom_unit_vector, r->normal);
    s.bottom_length = r->bottom_length;
    s.side_length = r->side_length;
  } else {
    const DiskFilter& d = std::get<DiskFilter>(f);
    s.disk = true;
    s.origin = d.center;
    s.normal = d.normal;
    s.radius = d.radius;
  }
  return s;
}

/// The signed distance of x to the shape's plane.
double side_of(const Shape& s, const Vec& x) { return dot(minus(x, s.origin), s.normal); }

/// Where the bond a-b meets the filter's plane (the header's convention), if it does.
std::optional<Vec> meets_plane(const Shape& s, const Vec& a, const Vec& b) {
  const double sa = side_of(s, a), sb = side_of(s, b);
  if ((sa > 0 && sb > 0) || (sa < 0 && sb < 0) || (sa == 0 && sb == 0)) return std::nullopt;
  const double t = sa / (sa - sb);
  return Vec{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

/// x's coordinates along a rectangle's bottom and side, from its lower left corner.
std::pair<double, double> rectangle_coordinates(const Shape& s, const Vec& x) {
  const Vec r = minus(x, s.origin);
  return {dot(r, s.bottom), dot(r, s.side)};
}

/// Whether x, in the shape's plane, lies on the shape.
bool inside(const Shape& s, const Vec& x) {
  if (s.disk) {
    const Vec r = minus(x, s.origin);
    return dot(r, r) < s.radius * s.radius;
  }
  const auto [along_bottom, along_side] = rectangle_coordinates(s, x);
  return along_bottom >= 0 && along_bottom <= s.bottom_length && along_side >= 0 && along_side <= s.side_length;
}

bool cuts(const Shape& s, const Vec& a, const Vec& b) {
  const std::optional<Vec> x = meets_plane(s, a, b);
  return x && inside(s, *x);
}

Vec point(PointView p, std::size_t i) { return {p(i, 0), p(i, 1), p.dims() == 3 ? p(i, 2) : 0.0}; }

/// Per point, which filters' planes it lies strictly above and below (bit f), which it is
/// near: within `reach` of the plane and of the shape's extent, and, of those, which it lies
/// deep within: its projection on the plane inside the shape by a margin far above rounding.
/// A bond can only cross filter f when its ends are not both above nor both below, and, when no
/// longer than `reach`, only when both are near f (so rows of points near no filter are kept
/// whole). A bond whose ends lie strictly on both sides of f and deep within it crosses f
/// inside the shape (the crossing lies between the ends' projections, and the shape is convex):
/// cut without `cuts`. One struct per point: a bond's test reads its other end's masks from one
/// cache line.
struct Sides {
  std::uint64_t above = 0, below = 0, near = 0, deep = 0;
};

bool within_reach(const Shape& s, const Vec& x, double side, double reach) {
  if (!(std::abs(side) < reach)) return false;
  if (!s.disk) {
    const auto [along_bottom, along_side] = rectangle_coordinates(s, x);
    return along_bottom > -reach && along_bottom < s.bottom_length + reach && along_side > -reach &&
           along_side < s.side_length + reach;
  }
  const Vec d = minus(x, s.origin);
  return dot(d, d) < (s.radius + reach) * (s.radius + reach);
}

/// Whether x's projection lies inside the shape by at least `margin`.
bool deep_within(const Shape& s, const Vec& x, double margin) {
  if (!s.disk) {
    const auto [along_bottom, along_side] = rectangle_coordinates(s, x);
    return along_bottom >= margin && along_bottom <= s.bottom_length - margin && along_side >= margin &&
           along_side <= s.side_length - margin;
  }
  // x projected on the plane, relative to the centre: no cancellation of large squares.
  const Vec d = minus(x, s.origin);
  const double along_normal = dot(d, s.normal) / dot(s.normal, s.normal);
  const Vec r{d[0] - along_normal * s.normal[0], d[1] - along_normal * s.normal[1], d[2] - along_normal * s.normal[2]};
  return s.radius > margin && dot(r, r) < (s.radius - margin) * (s.radius - margin);
}

/// A margin far above the rounding of `cuts`: a few ulps of the largest magnitude it meets (the
/// coordinates of either point set in `box`, the shape's origin and extent), times its vectors'
/// (unit, unless a caller broke that contract).
double deep_margin(const Shape& s, const Bounds& box) {
  double scale = s.bottom_length + s.side_length + s.radius, vectors = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    scale += std::max(std::abs(box.lo[a]), std::abs(box.hi[a])) + std::abs(s.origin[a]);
    vectors += std::abs(s.normal[a]) + std::abs(s.bottom[a]) + std::abs(s.side[a]);
  }
  return scale * vectors * 0x1p-36;
}

/// `margin`: deep_margin of each shape.
ScratchBuffer<Sides> sides_of(PointView points, const std::vector<Shape>& shapes, const std::vector<double>& margin,
                              double reach, int threads) {
  const auto n = static_cast<std::int64_t>(points.size());
  ScratchBuffer<Sides> sides(points.size());  // not zeroed: each is written once below
  // A margin for the rounding of the dot products (bond lengths and offsets are O(reach) here).
  const double padded = reach > 0 ? reach * (1 + 1e-6) : std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec x = point(points, static_cast<std::size_t>(i));
    Sides s;
    for (std::size_t f = 0; f < shapes.size(); ++f) {
      const double side = side_of(shapes[f], x);
      s.above |= std::uint64_t{side > 0} << f;
      s.below |= std::uint64_t{side < 0} << f;
      // Only a bond with both ends near f can cross it: deep is of no use to the others.
      const bool near = within_reach(shapes[f], x, side, padded);
      s.near |= std::uint64_t{near} << f;
      s.deep |= std::uint64_t{near && deep_within(shapes[f], x, margin[f])} << f;
    }
    sides[static_cast<std::size_t>(i)] = s;
  }
  return sides;
}

}  // namespace

bool cuts(const BondFilter& filter, const double* a, const double* b) {
  return cuts(shape_of(filter), {a[0], a[1], a[2]}, {b[0], b[1], b[2]});
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
  std::vector<Shape> shapes(filters.size());
  std::transform(filters.begin(), filters.end(), shapes.begin(), shape_of);
  const Bounds box = one_set ? bounds_of(rows, threads) : bounds_of(rows, columns, threads);
  std::vector<double> margin(shapes.size());
  for (std::size_t f = 0; f < shapes.size(); ++f) margin[f] = deep_margin(shapes[f], box);
  const ScratchBuffer<Sides> row_sides = sides_of(rows, shapes, margin, reach, threads);
  const ScratchBuffer<Sides> column_sides =
      one_set ? ScratchBuffer<Sides>{} : sides_of(columns, shapes, margin, reach, threads);
  const Sides* col = one_set ? row_sides.data() : column_sides.data();

  const std::uint64_t all = filters.size() == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << filters.size()) - 1;
  // Whether the bond i-j survives every filter whose plane it may cross.
  auto kept = [&](std::size_t i, point_id j) {
    const Sides &at_i = row_sides[i], &at_j = col[j];
    const std::uint64_t across = (at_i.above & at_j.below) | (at_i.below & at_j.above);
    if (across & at_i.deep & at_j.deep) return false;
    const std::uint64_t same_side = (at_i.above & at_j.above) | (at_i.below & at_j.below);
    std::uint64_t candidates = ~same_side & at_i.near & at_j.near & all;
    if (!candidates) return true;
    Vec a = point(rows, i), b = point(columns, static_cast<std::size_t>(j));
    if (one_set && static_cast<std::size_t>(j) < i) std::swap(a, b);  // a: the smaller id's end
    for (; candidates; candidates &= candidates - 1)
      if (cuts(shapes[static_cast<std::size_t>(std::countr_zero(candidates))], a, b)) return false;
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
