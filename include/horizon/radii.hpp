#pragma once
/// \file radii.hpp
/// Per-point horizons: every point i has its own radius r_i, and a rule says which radius a
/// pair i-j is tested with. The pair test is the search's own (metric.hpp) with that radius as
/// the horizon, the nearest periodic image counting in a box.
#include <span>
#include <string>

#include "horizon/neighbor_list.hpp"
#include "horizon/search.hpp"

namespace horizon {

enum class RadiusRule {
  gather,   ///< row i holds j when d(i, j) < r_i (scipy's query_ball_point with an array of r)
  scatter,  ///< d(i, j) < r_j: the points whose radius reaches i
  max,      ///< d(i, j) < max(r_i, r_j) (symmetric)
  min,      ///< d(i, j) < min(r_i, r_j) (symmetric)
  sum,      ///< d(i, j) < r_i + r_j (symmetric; ASE's per-atom cutoffs)
};

/// The horizon `rule` gives the pair of points with radii r_i and r_j.
inline double pair_radius(RadiusRule rule, double r_i, double r_j) {
  switch (rule) {
    case RadiusRule::gather: return r_i;
    case RadiusRule::scatter: return r_j;
    case RadiusRule::max: return r_i > r_j ? r_i : r_j;
    case RadiusRule::min: return r_i < r_j ? r_i : r_j;
    case RadiusRule::sum: return r_i + r_j;
  }
  return 0;
}
/// "gather", "scatter", "max", "min", "sum" (the CLI spelling) and back.
RadiusRule parse_radius_rule(const std::string& name);
const char* radius_rule_name(RadiusRule rule);

/// The neighbour list of `points` against themselves with one radius per point (`radii`, each
/// finite and > 0) combined by `rule`; options.horizon is ignored, everything else applies
/// (backend, metric, k, box: every radius below half the period). Half lists only with max or
/// min. Rows come out sorted.
///
/// Points are searched in radius classes (radii within a factor 4 of the class's largest), each
/// as queries among all points at its largest radius, then tested with their own: radii that
/// span a wide range cost a few searches, never the whole range's stencil at the largest radius.
/// Throws horizon::Error naming the first bad radius or the bad combination.
NeighborList search_with_radii(PointView points, std::span<const double> radii, RadiusRule rule,
                               const SearchOptions& options, SearchStats* stats = nullptr);

/// The families of `queries` among `references`, each query with its own radius (`radii`, one
/// per query): row q holds every reference r with d(q, r) < radii[q] (the gather rule; nothing
/// is excluded as "self"); ids index `references`. Full lists only.
NeighborList search_with_radii(PointView queries, std::span<const double> radii, PointView references,
                               const SearchOptions& options, SearchStats* stats = nullptr);

/// The brute-force answers (O(N^2)): every pair tested with the radius `rule` gives it; and
/// every query against every reference with the query's radius.
NeighborList brute_force_with_radii(PointView points, std::span<const double> radii, RadiusRule rule,
                                    const SearchOptions& options);
NeighborList brute_force_with_radii(PointView queries, std::span<const double> radii, PointView references,
                                    const SearchOptions& options);

}  // namespace horizon
