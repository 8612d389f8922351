#pragma once
// How a search cut into parts (partitioned_search.cpp, parts.hpp) finds each part's points:
// the parts' boxes by recursive coordinate bisection, then every part's lists in two passes over
// the points on all cores.
#include <cstdint>
#include <vector>

#include "horizon/buffer.hpp"
#include "horizon/decomposition.hpp"
#include "horizon/points.hpp"

namespace horizon::detail {

/// One part's points, as ascending ids. The host path reads `owned` and `halo`; a GPU part reads
/// `owned` and `global`, its own points and its halo in one ascending order (its local points:
/// a local list's rows are then sorted in global ids too, and a half list keeps j > i globally),
/// with `owned_rows`, the local rows of its own points.
struct PartLists {
  ScratchBuffer<point_id> owned, halo, global, owned_rows;
  std::size_t halo_count = 0;
};

class PartCut {
public:
  /// The boxes of `count` parts (1 to 64) of equal point count, placed on a sample of at most
  /// 2^17 points (equal counts to within a fraction of a percent without sorting all the
  /// points), and the reach of their halos.
  PartCut(PointView points, int count, double horizon);

  /// Every part's lists: `owned` and `halo`, or with `local` (GPU parts) `owned`, `global` and
  /// `owned_rows`.
  std::vector<PartLists> lists(PointView points, bool local) const;

private:
  /// Point i's part, and its halo parts (bit p) in `halo`.
  int parts_of(PointView points, std::size_t i, std::uint64_t& halo) const;
  Decomposition boxes_;
  double reach_ = 0;
  int count_ = 1;
};

}  // namespace horizon::detail
