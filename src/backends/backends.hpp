#pragma once
// The backends behind horizon::search(). Each receives validated, non-empty points.
#include "horizon/search.hpp"

namespace horizon::detail {

/// What search(points, options) checks before it picks a backend: Error otherwise.
void validate_search(PointView points, const SearchOptions& options);

NeighborList search_serial(PointView points, const SearchOptions& options, SearchStats& stats);
NeighborList search_openmp(PointView points, const SearchOptions& options, SearchStats& stats);
bool openmp_built();
/// Defined in cuda/ when built with CUDA; otherwise throws.
NeighborList search_cuda(PointView points, const SearchOptions& options, SearchStats& stats);
bool cuda_usable();

}  // namespace horizon::detail
