#pragma once
// One process, several devices (thesis ch. 5: overlapping partitions, no communication): the
// points are cut into parts of equal point count by recursive coordinate bisection; each part
// is searched, with the points within the horizon of its box as references only, by its own
// host thread; its rows, mapped to global ids, are then copied into the list in input order.
#include <cstdint>
#include <span>
#include <vector>

#include "horizon/search.hpp"

namespace horizon::detail {

/// The rows of the first `owned` points of `list`, a full list of local points (owned points
/// first, then references), with ids mapped through `global`. Each local row is two runs
/// ascending in global id (owned, then references) when `global` ascends within each: one
/// merge sorts it. Half lists keep j > i by global id (local ids do not order globally).
/// Shared by the multi-device driver and the distributed search; parallel over rows. For a list
/// of queries among local references, `references_from` is where the second run starts.
NeighborList rows_in_global_ids(const NeighborList& list, std::span<const point_id> global, std::size_t owned,
                                bool half, bool sort_rows, std::size_t references_from = SIZE_MAX);

/// The list of `points` from one search per entry of `part_options` (each a node-local search:
/// a backend and, for cuda, a device). stats.parts gets each part's points, entries and time;
/// stats.search_seconds covers everything: cutting, the parts (in parallel) and the assembly.
NeighborList search_parts(PointView points, const SearchOptions& options,
                          const std::vector<SearchOptions>& part_options, SearchStats& stats);

}  // namespace horizon::detail
