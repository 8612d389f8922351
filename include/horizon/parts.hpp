#pragma once
/// \file parts.hpp
/// Overlapping partitions (thesis ch. 5): the points cut into parts of equal point count by
/// recursive coordinate bisection, each part with its halo, the points within the horizon of
/// its box. A part's rows need only its own points and its halo, so parts are searched with
/// no communication between them: one per GPU (cuda.hpp: search_device_parts), or here on the
/// CPU, where each part is a node-local search of its own.
#include <cstddef>
#include <vector>

#include "horizon/neighbor_list.hpp"
#include "horizon/points.hpp"
#include "horizon/search.hpp"

namespace horizon {

/// The points of one part, as ids into the points that were cut.
struct PointPart {
  std::vector<point_id> owned;  ///< ascending: every point is owned by exactly one part
  std::vector<point_id> halo;   ///< ascending: the other points within the horizon of its box
};

/// Cuts `points` into `parts` parts (1 to 64) as the multi-GPU search does: boxes of equal
/// point count, each part's halo reaching options.horizon beyond its box. Throws horizon::Error
/// for a periodic box or cell (parts are for open boundaries).
std::vector<PointPart> cut_into_parts(PointView points, int parts, const SearchOptions& options);

/// One part's rows, in global ids.
struct OwnedPart {
  std::vector<point_id> ids;  ///< the global id of each row: the part's owned points, ascending
  std::size_t halo = 0;       ///< points searched as references only
  /// Row r: the neighbours of point ids[r], as global ids, sorted when options.sort_rows; a
  /// half list keeps j > i by global id.
  NeighborList rows;
};

/// The list of `points` cut into `parts` parts, each searched in turn with options' CPU backend
/// (all its threads on one part): the rows of every point, once, in the part that owns it. The
/// CPU counterpart of search_device_parts, with the same parts.
std::vector<OwnedPart> search_in_parts(PointView points, int parts, const SearchOptions& options);

}  // namespace horizon
