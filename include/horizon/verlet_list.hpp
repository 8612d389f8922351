#pragma once
/// \file verlet_list.hpp
/// A Verlet list for moving points: the pairs within horizon + skin, searched once, from which
/// the exact horizon list of later positions is filtered until some point has moved more than
/// skin / 2 (then two points can have closed the gap of a skin and a search is needed again).
#include <vector>

#include "horizon/neighbor_list.hpp"
#include "horizon/points.hpp"
#include "horizon/search.hpp"

namespace horizon {

class VerletList {
public:
  /// Searches `points` with `options` (any backend, metric, half list) widened by `skin` > 0.
  /// Periodic boxes are not supported (throws).
  VerletList(PointView points, const SearchOptions& options, double skin);

  /// True once a point has moved (in the options' metric) by skin / 2 or more since the build,
  /// less 1e-9 (horizon + skin) so that rounding never lets refresh() miss a pair. Throws when
  /// the number of points or the dimension changed.
  bool needs_rebuild(PointView points, int threads = 0) const;

  /// The exact list of `points` within the horizon, filtered from the stored candidates with the
  /// search's arithmetic: equal to search(points, options) while !needs_rebuild(points).
  NeighborList refresh(PointView points, int threads = 0) const;

  /// The pairs within horizon + skin of the positions at the build.
  const NeighborList& candidates() const { return candidates_; }

private:
  void check_shape(PointView points) const;

  SearchOptions options_;
  double skin_;
  PointSet built_at_;  ///< the positions at the build
  NeighborList candidates_;
};

}  // namespace horizon
