#pragma once
// The periodic images a cell search works on: the points wrapped into the cell along its
// periodic vectors, and each wrapped point's images within the horizon of the cell (however
// many cells away), as points of their own. The one-node cell search and the distributed one
// both search them and map each candidate back to its point and shift.
#include <cstdint>

#include "cell_problem.hpp"
#include "horizon/buffer.hpp"
#include "horizon/points.hpp"

namespace horizon::detail {

/// Points wrapped into the cell on its periodic axes, and their images: the wrapped points
/// first (the queries), then each point's images in (point, shift) order.
struct Images {
  int dims = 3;
  ScratchBuffer<double> original;     ///< the caller's coordinates as doubles
  ScratchBuffer<double> xyz;          ///< wrapped points, then images
  ScratchBuffer<std::int32_t> wraps;  ///< per point: the cells it was moved by (x = wrapped + w . cell)
  ScratchBuffer<point_id> image_of;   ///< per image: its point
  ScratchBuffer<std::int32_t> image_shift;  ///< per image: its shift G from the wrapped point
};

/// The images of `points` within the problem's largest horizon (plus `reach_margin`) of the
/// cell. Error when a point lies more than 2^30 cells away, or the points and images would
/// number 2^31 or more.
Images make_images(PointView points, const CellProblem& problem, double reach_margin, int threads);

/// The margin the candidates' search adds to the horizon, covering the rounding of wrapped and
/// image coordinates: relative to `extent` (the largest |coordinate| of any point, at least the
/// largest horizon), the cell vectors and the horizon.
double image_margin(double extent, const CellProblem& problem);

}  // namespace horizon::detail
