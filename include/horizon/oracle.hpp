#pragma once
/// \file oracle.hpp
/// The brute-force O(N^2) answer every backend is checked against: each pair tested once with
/// the same metric arithmetic, no grid involved.
#include <vector>

#include "horizon/neighbor_list.hpp"
#include "horizon/search.hpp"

namespace horizon {

/// The whole list (full or half, as options.half says; rows sorted; with options.queries, only
/// points 0 .. queries-1 get rows; with options.box, the nearest periodic image counts).
NeighborList brute_force(PointView points, const SearchOptions& options);

/// The families of `queries` among `references` (search's second form).
NeighborList brute_force(PointView queries, PointView references, const SearchOptions& options);

/// The sorted family of point i alone (the half-list row when options.half), in O(N).
std::vector<point_id> brute_force_family(PointView points, std::size_t i,
                                         const SearchOptions& options);

}  // namespace horizon
