#pragma once
// The backends behind horizon::search(). Each receives validated, non-empty points.
#include <span>

#include "horizon/search.hpp"

namespace horizon::detail {

/// What search(points, options) checks before it picks a backend: Error otherwise.
void validate_search(PointView points, const SearchOptions& options);

/// The CPU backends. The last image_of.size() points may be periodic images (CellIndex): the
/// rows are those of the other points, the images found as the points they copy.
NeighborList search_serial(PointView points, const SearchOptions& options, SearchStats& stats,
                           std::span<const point_id> image_of = {});
NeighborList search_openmp(PointView points, const SearchOptions& options, SearchStats& stats,
                           std::span<const point_id> image_of = {});
bool openmp_built();
/// Defined in cuda/ when built with CUDA; otherwise throws.
NeighborList search_cuda(PointView points, const SearchOptions& options, SearchStats& stats);
bool cuda_usable();

}  // namespace horizon::detail
