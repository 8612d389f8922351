#pragma once
// The backends behind horizon::search(). Each receives validated, non-empty points.
#include "horizon/search.hpp"

namespace horizon::detail {

NeighborList search_serial(PointView points, const SearchOptions& options, SearchStats& stats);
NeighborList search_openmp(PointView points, const SearchOptions& options, SearchStats& stats);
bool openmp_built();
/// Defined in cuda/ when built with CUDA; otherwise throws.
NeighborList search_cuda(PointView points, const SearchOptions& options, SearchStats& stats);
bool cuda_usable();

}  // namespace horizon::detail
