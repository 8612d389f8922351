#include "cell_images.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "horizon/error.hpp"
#include "parallel_scan.hpp"

namespace horizon::detail {
namespace {

/// The range [lo, hi] of shifts along a periodic axis for a point at wrapped fractional
/// coordinate f: every image within `reach` cells of the cell [0, 1).
void shift_range(double f, double reach, std::int64_t& lo, std::int64_t& hi) {
  lo = static_cast<std::int64_t>(std::ceil(-reach - f));
  hi = static_cast<std::int64_t>(std::floor(1 + reach - f));
  lo = std::min<std::int64_t>(lo, 0);  // the point itself, whatever rounding made of f
  hi = std::max<std::int64_t>(hi, 0);
}

}  // namespace

Images make_images(PointView points, const CellProblem& problem, double reach_margin, int threads) {
  const int dims = points.dims();
  const auto n = static_cast<std::int64_t>(points.size());
  const CellFrame& frame = problem.frame;
  Images images;
  images.dims = dims;
  images.original = ScratchBuffer<double>(points.size() * dims);
  images.wraps = ScratchBuffer<std::int32_t>(points.size() * 3);
  ScratchBuffer<double> fractional(points.size() * 3);
  ScratchBuffer<std::int64_t> first(points.size() + 1);
  double reach[3] = {0, 0, 0};
  for (int a = 0; a < dims; ++a)
    if (frame.pbc[a]) reach[a] = problem.cells_reach(a) * (1 + 1e-12) + reach_margin / frame.height[a];
  // Ranges are per point (a point's own fraction decides which images are near the cell).
  std::int64_t too_far = n;
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1 && n > 4096) reduction(min : too_far)
  for (std::int64_t i = 0; i < n; ++i) {
    double* x = images.original.data() + i * dims;
    for (int a = 0; a < dims; ++a) x[a] = points(static_cast<std::size_t>(i), a);
    std::int64_t count = 1;
    for (int a = 0; a < 3; ++a) {
      std::int32_t w = 0;
      double f = 0;
      if (a < dims && frame.pbc[a]) {
        f = frame.fractional(x, a);
        const double cells = std::floor(f);
        if (!(std::fabs(cells) < 0x1p30)) too_far = std::min(too_far, i);
        w = std::fabs(cells) < 0x1p30 ? static_cast<std::int32_t>(cells) : 0;
        f -= w;
        std::int64_t lo, hi;
        shift_range(f, reach[a], lo, hi);
        count *= hi - lo + 1;
      }
      images.wraps[i * 3 + a] = w;
      fractional[i * 3 + a] = f;
    }
    first[i + 1] = count - 1;  // the point's own copy is a query, not an image
  }
  if (too_far < n)
    throw Error("point " + std::to_string(too_far) + " lies more than 2^30 cells away from the cell");
  first[0] = 0;
  inclusive_scan(first.data() + 1, points.size(), threads);
  const auto total = static_cast<std::size_t>(first[n]);
  if (total + points.size() >= static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error("cell: the points and their " + std::to_string(total) +
                " periodic images within the horizon must be fewer than 2^31 - 1 (a horizon of many cells?)");
  images.xyz = ScratchBuffer<double>((points.size() + total) * dims);
  images.image_of = ScratchBuffer<point_id>(total);
  images.image_shift = ScratchBuffer<std::int32_t>(total * 3);
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads) if (threads > 1 && n > 4096)
  for (std::int64_t i = 0; i < n; ++i) {
    const double* x = images.original.data() + i * dims;
    const std::int32_t* w = images.wraps.data() + i * 3;
    double wrapped[3] = {0, 0, 0};
    for (int a = 0; a < dims; ++a) {
      double moved = 0;
      for (int k = 0; k < dims; ++k) moved += w[k] * frame.vectors[k][a];
      wrapped[a] = x[a] - moved;
      images.xyz[i * dims + a] = wrapped[a];
    }
    std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int a = 0; a < dims; ++a)
      if (frame.pbc[a]) shift_range(fractional[i * 3 + a], reach[a], lo[a], hi[a]);
    std::size_t at = static_cast<std::size_t>(first[i]);
    for (std::int64_t g0 = lo[0]; g0 <= hi[0]; ++g0)
      for (std::int64_t g1 = lo[1]; g1 <= hi[1]; ++g1)
        for (std::int64_t g2 = lo[2]; g2 <= hi[2]; ++g2) {
          if (g0 == 0 && g1 == 0 && g2 == 0) continue;
          const std::int64_t g[3] = {g0, g1, g2};
          double* image = images.xyz.data() + (points.size() + at) * dims;
          for (int a = 0; a < dims; ++a) {
            double moved = 0;
            for (int k = 0; k < dims; ++k) moved += static_cast<double>(g[k]) * frame.vectors[k][a];
            image[a] = wrapped[a] + moved;
          }
          images.image_of[at] = static_cast<point_id>(i);
          for (int a = 0; a < 3; ++a) images.image_shift[at * 3 + a] = static_cast<std::int32_t>(g[a]);
          ++at;
        }
  }
  return images;
}

double image_margin(double extent, const CellProblem& problem) {
  double cell_extent = 0;
  for (int k = 0; k < problem.dims(); ++k)
    if (problem.frame.pbc[k]) cell_extent += problem.frame.scale * (2 + problem.cells_reach(k));
  return 0x1p-40 * (extent + cell_extent + problem.largest);
}

}  // namespace horizon::detail
