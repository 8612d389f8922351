#include "horizon/bond_filter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <omp.h>

#include "bond_kernel.hpp"
#include "select_entries.hpp"
#include "horizon/error.hpp"
#include "horizon/grid.hpp"

namespace horizon {

using detail::BondMasks;
using detail::DecideBond;

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

/// A bond can only cross filter f when its ends are not both above nor both below its plane,
/// and, when no longer than `reach`, only when both are near f (so rows of points near no filter
/// are kept whole); the ends' masks (BondMasks) decide most bonds near f (keep_bonds).
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

constexpr std::uint64_t near_field = std::uint64_t{0xFFFF} << BondMasks::near;

/// Each point's BondMasks for shapes[first, first + 16) (at most); `margin`: deep_margin of each shape.
ScratchBuffer<std::uint64_t> masks_of(PointView points, const std::vector<Shape>& shapes, std::size_t first,
                                      const std::vector<double>& margin, double reach, int threads) {
  detail::Planes planes{};
  planes.count = static_cast<int>(std::min(shapes.size() - first, std::size_t{BondMasks::filters}));
  for (int f = 0; f < planes.count; ++f)
    for (int a = 0; a < 3; ++a) {
      planes.origin[a][f] = shapes[first + static_cast<std::size_t>(f)].origin[a];
      planes.normal[a][f] = shapes[first + static_cast<std::size_t>(f)].normal[a];
    }
  ScratchBuffer<std::uint64_t> masks(points.size());  // not zeroed: each is written once below
  // A margin for the rounding of the dot products (bond lengths and offsets are O(reach) here).
  const double padded = reach > 0 ? reach * (1 + 1e-6) : std::numeric_limits<double>::infinity();
  constexpr std::int64_t block = 4096;
  const auto blocks = static_cast<std::int64_t>((points.size() + block - 1) / block);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const auto begin = static_cast<std::size_t>(b * block), end = std::min(points.size(), begin + block);
    detail::plane_sides(points, begin, end, planes, padded, masks.data());
    // Of the planes a point is close to, the shapes it is near (deep is of no use to the others:
    // only a bond with both ends near f can cross it).
    for (std::size_t i = begin; i < end; ++i) {
      std::uint64_t close = masks[i] >> BondMasks::near, near = 0, deep = 0;
      if (!close) continue;
      const Vec x = point(points, i);
      for (; close; close &= close - 1) {
        const auto f = static_cast<std::size_t>(std::countr_zero(close));
        const Shape& shape = shapes[first + f];
        if (!within_reach(shape, x, side_of(shape, x), padded)) continue;
        near |= std::uint64_t{1} << f;
        deep |= std::uint64_t{deep_within(shape, x, margin[first + f])} << f;
      }
      masks[i] = (masks[i] & ~near_field) | near << BondMasks::near | deep << BondMasks::deep;
    }
  }
  return masks;
}

}  // namespace

bool cuts(const BondFilter& filter, const double* a, const double* b) {
  return cuts(shape_of(filter), {a[0], a[1], a[2]}, {b[0], b[1], b[2]});
}

namespace {

/// The bonds of `list` that cross none of shapes[first, first + 16) (at most).
NeighborList filter_some(NeighborList list, PointView rows, PointView columns, bool one_set,
                         const std::vector<Shape>& shapes, std::size_t first, const std::vector<double>& margin,
                         double reach, int threads) {
  const ScratchBuffer<std::uint64_t> row_masks = masks_of(rows, shapes, first, margin, reach, threads);
  const ScratchBuffer<std::uint64_t> column_masks =
      one_set ? ScratchBuffer<std::uint64_t>{} : masks_of(columns, shapes, first, margin, reach, threads);
  const std::uint64_t* column = one_set ? row_masks.data() : column_masks.data();

  // The bond from row i to id j that the masks left open, decided by `cuts`.
  struct Row {
    const Shape* shapes;
    PointView rows, columns;
    bool one_set;
    std::size_t i;
  };
  const DecideBond decide = [](const void* context, point_id j, std::uint32_t filters) {
    const Row& row = *static_cast<const Row*>(context);
    Vec a = point(row.rows, row.i), b = point(row.columns, static_cast<std::size_t>(j));
    if (row.one_set && static_cast<std::size_t>(j) < row.i) std::swap(a, b);  // a: the smaller id's end
    for (; filters; filters &= filters - 1)
      if (cuts(row.shapes[std::countr_zero(filters)], a, b)) return false;
    return true;
  };
  // Rows of points near no filter (with a known reach) need no tests.
  return detail::compact_rows(
      std::move(list), [&](std::size_t i) { return (row_masks[i] & near_field) == 0; },
      [&](std::size_t i, point_id* ids, std::int64_t count) {
        const Row row{shapes.data() + first, rows, columns, one_set, i};
        return detail::keep_bonds(row_masks[i], column, ids, count, decide, &row);
      },
      threads);
}

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
  // Sixteen filters at a time: a bond is kept when it crosses none of any group.
  for (std::size_t first = 0; first < shapes.size(); first += BondMasks::filters)
    list = filter_some(std::move(list), rows, columns, one_set, shapes, first, margin, reach, threads);
  return list;
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
