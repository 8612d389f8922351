#pragma once
// The periodic images a cell search works on: the points wrapped into the cell along its
// periodic vectors, and each wrapped point's images within the horizon of the cell (however
// many cells away), as points of their own. The one-node cell search and the distributed one
// both search them and map each candidate back to its point and shift.
#include <math.h>

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

/// The range [lo, hi] of shifts along a periodic axis for a point at wrapped fractional
/// coordinate f: every image within `reach` cells of the cell [0, 1).
HORIZON_HOST_DEVICE inline void shift_range(double f, double reach, std::int64_t& lo, std::int64_t& hi) {
  lo = static_cast<std::int64_t>(ceil(-reach - f));
  hi = static_cast<std::int64_t>(floor(1 + reach - f));
  lo = lo < 0 ? lo : 0;  // the point itself, whatever rounding made of f
  hi = hi > 0 ? hi : 0;
}

/// Point x wrapped into the cell on its periodic axes: w, the cells it is moved by (x = wrapped +
/// w . cell), the wrapped point's fractional coordinates f, and `images`, how many images it
/// has within `reach` cells (per axis) beside itself. False when x lies 2^30 cells or more away.
HORIZON_HOST_DEVICE inline bool wrap_into_cell(const double* x, const CellFrame& frame, const double* reach,
                                               std::int32_t* w, double* f, std::int64_t& images) {
  bool near = true;
  std::int64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    w[a] = 0;
    f[a] = 0;
    if (a >= frame.dims || !frame.pbc[a]) continue;
    f[a] = frame.fractional(x, a);
    const double cells = floor(f[a]);
    near = near && fabs(cells) < 0x1p30;
    w[a] = fabs(cells) < 0x1p30 ? static_cast<std::int32_t>(cells) : 0;
    f[a] -= w[a];
    std::int64_t lo, hi;
    shift_range(f[a], reach[a], lo, hi);
    count *= hi - lo + 1;
  }
  images = count - 1;  // the point's own copy is a query, not an image
  return near;
}

/// The images of wrapped point i (its fractional coordinates f) in shift order, at `xyz`
/// (dims coordinates each), their point at `image_of` and shift G at `shift` (3 each).
HORIZON_HOST_DEVICE inline void write_images(const double* wrapped, const double* f, point_id i, const CellFrame& frame,
                                             const double* reach, double* xyz, point_id* image_of, std::int32_t* shift) {
  std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int a = 0; a < frame.dims; ++a)
    if (frame.pbc[a]) shift_range(f[a], reach[a], lo[a], hi[a]);
  for (std::int64_t g0 = lo[0]; g0 <= hi[0]; ++g0)
    for (std::int64_t g1 = lo[1]; g1 <= hi[1]; ++g1)
      for (std::int64_t g2 = lo[2]; g2 <= hi[2]; ++g2) {
        if (g0 == 0 && g1 == 0 && g2 == 0) continue;
        const std::int64_t g[3] = {g0, g1, g2};
        for (int a = 0; a < frame.dims; ++a) xyz[a] = wrapped[a] + cells_along(g, frame, frame.dims, a);
        xyz += frame.dims;
        *image_of++ = i;
        for (int a = 0; a < 3; ++a) *shift++ = static_cast<std::int32_t>(g[a]);
      }
}

/// The reach per axis, in cells, of the images a cell search makes: the problem's largest
/// horizon plus `reach_margin`, and 0 on open axes.
void images_reach(const CellProblem& problem, double reach_margin, double* reach);

/// The images of `points` within the problem's largest horizon (plus `reach_margin`) of the
/// cell. Error when a point lies more than 2^30 cells away, or the points and images would
/// number 2^31 or more.
Images make_images(PointView points, const CellProblem& problem, double reach_margin, int threads);

/// The margin the candidates' search adds to the horizon, covering the rounding of wrapped and
/// image coordinates: relative to `extent` (the largest |coordinate| of any point, at least the
/// largest horizon), the cell vectors and the horizon.
double image_margin(double extent, const CellProblem& problem);

}  // namespace horizon::detail
