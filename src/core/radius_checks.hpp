#pragma once
// The checks every search with per-point radii makes (the grid's, radii_search.cpp, and the
// cell search's): one radius per point, each finite and > 0, a symmetric rule for half lists.
#include <cstddef>
#include <span>
#include <string>

#include "horizon/radii.hpp"

namespace horizon::detail {

/// Error naming the first bad radius or the bad combination; `one` and `many` name what
/// carries the radii: point(s) or quer(y|ies).
void check_radii(std::size_t count, std::span<const double> radii, RadiusRule rule, bool half,
                 const std::string& one = "point", const std::string& many = "points");

}  // namespace horizon::detail
