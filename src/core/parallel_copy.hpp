#pragma once
// Copies on all cores: one core cannot keep up with PCIe when the destination's pages are
// touched for the first time.
#include <cstddef>

#include "horizon/points.hpp"

namespace horizon::detail {

void parallel_copy(void* to, const void* from, std::size_t bytes);

/// Coordinates [first, first + count) of `points` (flattened, point after point) as doubles.
void parallel_copy_coordinates(double* to, PointView points, std::size_t first, std::size_t count);

/// Touches every page of [at, at + bytes) once, so that later copies into it do not fault.
void parallel_touch(void* at, std::size_t bytes);

}  // namespace horizon::detail
