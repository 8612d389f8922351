#pragma once
// The test of a row's bonds against up to 16 bond filters from their ends' masks
// (bond_filter.cpp), compiled for each SIMD instruction set with the best one this CPU has
// picked at run time: a scalar test per bond was issue-bound (15 cycles a bond, AMD Zen 5).
#include <cstdint>

#include "horizon/neighbor_list.hpp"
#include "horizon/points.hpp"

namespace horizon::detail {

/// A point's masks for up to 16 filters in one word, bit f of each field for filter f: the
/// planes it lies strictly above and below, the filters it is near (within reach of the plane
/// and of the shape's extent), and of those the ones it lies deep within (its projection inside
/// the shape by a margin far above rounding).
struct BondMasks {
  static constexpr int above = 0, below = 16, near = 32, deep = 48;
  static constexpr int filters = 16;
};

/// Up to 16 planes, by coordinate: plane f passes through origin[.][f] with normal normal[.][f]
/// (unused lanes 0).
struct Planes {
  double origin[3][BondMasks::filters], normal[3][BondMasks::filters];
  int count;
};

/// For points [begin, end) (z = 0 in 2-D), masks[i]'s above and below fields, and in its near
/// field the planes closer than `reach`: |side| < reach, with side = (x - origin) . normal
/// computed as ((dx nx + dy ny) + dz nz), without fused multiply-adds, like the bond test's.
void plane_sides(PointView points, std::size_t begin, std::size_t end, const Planes& planes, double reach,
                 std::uint64_t* masks);

/// Decides the bond to `id` from the filters' geometry: whether it crosses none of `filters`
/// (bits), which the masks left open.
using DecideBond = bool (*)(const void* context, point_id id, std::uint32_t filters);

/// Keeps, in place and in order, the ids of row ids[0, count) whose bond to a point with masks
/// `own` crosses no filter: masks[id] are the other ends'. The masks decide most bonds (both
/// ends strictly on one side or both on the plane: kept; on both sides and both deep within, or
/// one end on the plane and deep within and the other off it: cut); `decide` the others.
/// Returns how many are kept.
std::int64_t keep_bonds(std::uint64_t own, const std::uint64_t* masks, point_id* ids, std::int64_t count,
                        DecideBond decide, const void* context);

}  // namespace horizon::detail
