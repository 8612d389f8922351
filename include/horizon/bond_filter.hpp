#pragma once
/// \file bond_filter.hpp
/// Peridynamic bond filters (Peridigm's two shapes): a bond i-j is dropped from the list when
/// the segment from x_i to x_j crosses a rectangle or a disk, e.g. a pre-notched crack.
///
/// Convention, exact in double precision: with s = (x - origin) . n the signed distance of an
/// end to the shape's plane, the bond meets the plane when its ends' s differ in sign or one is
/// 0, but not when both are 0 (a bond lying in the plane is kept); it meets it at
/// x_a + t (x_b - x_a), t = s_a / (s_a - s_b), a the end of the smaller id (so i-j and j-i agree).
/// The rectangle's edges count as inside, the disk's rim does not (as in Peridigm).
#include <array>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "horizon/neighbor_list.hpp"
#include "horizon/points.hpp"
#include "horizon/search.hpp"

namespace horizon {

/// A rectangle in the plane through `lower_left_corner` with unit `normal`: it spans
/// bottom_length along the unit `bottom_unit_vector` and side_length along bottom x normal.
struct RectangleFilter {
  std::array<double, 3> normal, lower_left_corner, bottom_unit_vector;
  double bottom_length = 0, side_length = 0;
};

/// A disk of `radius` about `center` in the plane with unit `normal`.
struct DiskFilter {
  std::array<double, 3> center, normal;
  double radius = 0;
};

using BondFilter = std::variant<RectangleFilter, DiskFilter>;

/// Most filters one call applies.
inline constexpr std::size_t max_bond_filters = 64;

/// Whether the bond from `a` (the end of the smaller id) to `b` crosses `filter` (3 coordinates each).
bool cuts(const BondFilter& filter, const double* a, const double* b);

/// `list` without the bonds that cross any of `filters`; rows keep their order. `rows` are the
/// list's points and `columns` the points its ids index (a query list); the overload without
/// `columns` is for a list of one point set. 2-D points lie in z = 0. `reach`: no bond of the
/// list is longer (bond_reach() of the search; 0: unknown), so rows of points farther than it
/// from every shape are kept whole without tests. `threads` 0: all cores. A list passed with
/// std::move is filtered in its own arrays (no second list is allocated).
/// Throws for more than max_bond_filters filters.
NeighborList filter_bonds(NeighborList list, PointView rows, PointView columns,
                          const std::vector<BondFilter>& filters, double reach = 0, int threads = 0);
NeighborList filter_bonds(NeighborList list, PointView points, const std::vector<BondFilter>& filters,
                          double reach = 0, int threads = 0);

/// The longest bond a search can give, for filter_bonds' `reach`.
inline double bond_reach(const SearchOptions& options, int dims) {
  return options.metric == Metric::chebyshev ? options.horizon * std::sqrt(static_cast<double>(dims)) : options.horizon;
}

/// Filters from a JSON array of {"type": "rectangle", "normal": [3], "lower_left_corner": [3],
/// "bottom_unit_vector": [3], "bottom_length": b, "side_length": a} and {"type": "disk",
/// "center": [3], "normal": [3], "radius": r}. Vectors are normalised; errors name the file, the
/// filter and the key.
std::vector<BondFilter> read_bond_filters(const std::string& path);

/// The same from JSON text; errors name `source` (e.g. the file or the argument it came from).
std::vector<BondFilter> parse_bond_filters(const std::string& json, const std::string& source);

}  // namespace horizon
