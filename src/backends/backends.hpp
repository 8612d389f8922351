#pragma once
// The backends behind horizon::search(). Each receives validated, non-empty points.
#include "horizon/cell_index.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// What search(points, options) checks before it picks a backend: Error otherwise. Without
/// `values`, the coordinates are left for the backend to check (all finite).
void validate_search(PointView points, const SearchOptions& options, bool values = true);

/// The CPU backends; periodic `images` join the points as references found as their originals.
NeighborList search_serial(PointView points, const SearchOptions& options, SearchStats& stats, Images images = {});
NeighborList search_openmp(PointView points, const SearchOptions& options, SearchStats& stats, Images images = {});
bool openmp_built();
/// Defined in cuda/ when built with CUDA; otherwise throws. Checks that the coordinates are
/// finite. A periodic options.box: checks the points against it and makes their images on the GPU.
NeighborList search_cuda(PointView points, const SearchOptions& options, SearchStats& stats);
bool cuda_usable();

}  // namespace horizon::detail
