#pragma once
// The search of an atomistic system: a periodic cell of any shape, horizons larger than the
// cell, every periodic image its own entry with its shift, and distances and vectors per entry.
// Built on the engine: the points wrapped into the cell, the images of each within the horizon
// of the cell made as points of their own (however many cells away), one query search of the
// wrapped points among them all, then each candidate tested again on the caller's coordinates
// with pair_vector(), the formula the oracle shares, so both take identical decisions.
#include <span>

#include "horizon/radii.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// Whether `options` need the cell path: a periodic cell, per-entry outputs or self_interaction.
bool needs_cell_search(const SearchOptions& options);

/// options.backend and options.threads as chosen already. `radii` (one per point, or empty for
/// options.horizon) are combined by `rule`.
NeighborList search_cell(PointView points, const SearchOptions& options, std::span<const double> radii,
                         RadiusRule rule, SearchStats& stats);

/// The same list by brute force: every i, j and every shift within reach, O(N^2 images).
NeighborList brute_force_cell(PointView points, const SearchOptions& options, std::span<const double> radii,
                              RadiusRule rule);

}  // namespace horizon::detail
