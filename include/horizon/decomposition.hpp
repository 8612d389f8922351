#pragma once
/// \file decomposition.hpp
/// Spatial decomposition of a bounding box into one axis-aligned sub-box per rank (thesis ch. 4
/// partitions by input order instead; see distributed.hpp). Pure geometry, no MPI: the
/// distributed search and the communication model share it.
#include <array>
#include <cstdint>
#include <vector>

#include "horizon/grid.hpp"
#include "horizon/points.hpp"

namespace horizon {

struct Box {
  std::array<double, 3> lo{}, hi{};
  /// Whether x lies in [lo, hi) on every axis (the owner test; the global box's upper faces
  /// are closed by the decomposition, see owner()).
  bool contains(const double* x, int dims) const;
  /// Whether x lies within `reach` of the box along every axis (Chebyshev distance < reach):
  /// every neighbour of an owned point, in any metric, satisfies it.
  bool near(const double* x, int dims, double reach) const;
};

/// The reach of a halo: the horizon widened by the rounding of the box tests and of the
/// distance differences, which grows with the coordinates' magnitude (not the box's extent:
/// points near 10^12 carry rounding errors of 10^-4).
double halo_reach(const Bounds& box, int dims, double horizon);

/// How the distributed layer cuts space among ranks: which rank owns each point.
class Decomposition {
public:
  /// brick: a grid of boxes fitted to the bounds; rcb: recursive coordinate bisection by point count.
  enum class Kind { brick, rcb };

  /// `ranks` bricks of a grid px x py x pz fitted to the box's shape (smallest cut area).
  static Decomposition brick(const Bounds& box, int dims, int ranks);
  /// Recursive coordinate bisection of `sample` by point count: each cut splits the points
  /// (and the ranks) of a box in proportion, along its longest axis.
  static Decomposition rcb(const Bounds& box, PointView sample, int ranks);

  int ranks() const { return static_cast<int>(boxes_.size()); }
  const Box& box(int rank) const { return boxes_[static_cast<std::size_t>(rank)]; }
  /// The rank owning point x: exactly one for every x inside the global box.
  int owner(const double* x) const;
  /// The rank owning x, and in `near` (bit r) every other rank whose box x is near (Box::near)
  /// within `reach`: one walk down the cuts, into both sides only within reach of a cut. At
  /// most 64 ranks.
  int owner_and_near(const double* x, double reach, std::uint64_t& near) const;
  /// Ranks whose box, widened by `reach`, holds some of rank's box: its halo partners.
  std::vector<int> partners(int rank, double reach) const;

private:
  struct Cut {
    int axis;
    double at;
    int below, above;  // children: >= 0 a node index, < 0 a rank (-1 - rank)
  };
  int dims_ = 3;
  std::vector<Box> boxes_;
  std::vector<Cut> tree_;  // tree_[0] is the root; empty when there is one rank
};

}  // namespace horizon
