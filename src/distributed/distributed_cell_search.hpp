#pragma once
// The distributed search of an atomistic system: a periodic cell of any shape, horizons larger
// than the cell, shifts, distances and vectors (cell_search.hpp on one node), across ranks.
//
// 1. A directory: every point goes to the rank that owns its id's block of [0, n), so each
//    rank holds a block of the caller's coordinates whatever split the caller chose.
// 2. Each rank wraps its block into the cell and makes its images within the horizon of the
//    cell; the images and the wrapped points are references numbered across ranks.
// 3. The distributed query search (halo or thesis exchange) finds, for every wrapped point, the
//    references within the horizon plus a rounding margin: the candidates.
// 4. Each rank asks the directory for its rows' points and the references' owners for what
//    each candidate is (j, its shift from j's coordinates, j's coordinates and radius), then
//    measures every candidate again on the caller's coordinates with pair_vector(), the
//    oracle's formula, and writes the kept entries in (j, S) order with their geometry.
#include <mpi.h>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "horizon/distributed.hpp"

namespace horizon::detail {

/// search_distributed() for options that need the cell path (needs_cell_search): with `rule`,
/// `radii` (one per held point) combined by it; without, options.search.horizon.
OwnedRows search_distributed_cell(MPI_Comm comm, PointView points, const std::vector<std::int64_t>& ids,
                                  std::span<const double> radii, const std::optional<RadiusRule>& rule,
                                  std::size_t global_count, const DistributedOptions& options,
                                  DistributedStats* stats);

}  // namespace horizon::detail
