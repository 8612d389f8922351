#pragma once
// Every pair of a few points tested, without a grid: the serial backend's search of up to
// all_pairs_points points (no periodic images, no query subset).
#include <cstddef>

#include "horizon/cell_index.hpp"
#include "horizon/neighbor_list.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// Up to this many points (a bit per pair, one word per row) the pairs cost less than the grid:
/// one core of the 2-core Zen 4 VM, random points, 10 points 5.8 -> 1.2 us, 64 points 13.7 ->
/// 5.0 us (the pairs grow as n^2: at 128 they would cost what the grid does).
constexpr std::size_t all_pairs_points = 64;

/// Whether search_all_pairs() takes this search: few points, no images, every point a row.
bool all_pairs_searchable(PointView points, const SearchOptions& options, const Images& images);

/// The list of `points` (at most all_pairs_points), every pair tested as the oracle does.
NeighborList search_all_pairs(PointView points, const SearchOptions& options);

}  // namespace horizon::detail
