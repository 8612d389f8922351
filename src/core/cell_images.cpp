#include "cell_images.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "horizon/error.hpp"
#include "parallel_for.hpp"
#include "parallel_scan.hpp"

namespace horizon::detail {
void images_reach(const CellProblem& problem, double reach_margin, double* reach) {
  const CellFrame& frame = problem.frame;
  for (int a = 0; a < 3; ++a)
    reach[a] = a < frame.dims && frame.pbc[a] ? problem.cells_reach(a) * (1 + 1e-12) + reach_margin / frame.height[a] : 0;
}

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
  double reach[3];
  images_reach(problem, reach_margin, reach);
  // Ranges are per point (a point's own fraction decides which images are near the cell).
  // A team only for many points; one thread enters no parallel region (parallel_for.hpp says
  // why; this loop's reduction keeps it out of parallel_for).
  const int team = n > 4096 ? threads : 1;
  const auto wrap = [&](std::int64_t i) {  // false: point i lies too far from the cell
    double* x = images.original.data() + i * dims;
    for (int a = 0; a < dims; ++a) x[a] = points(static_cast<std::size_t>(i), a);
    return wrap_into_cell(x, frame, reach, &images.wraps[i * 3], &fractional[i * 3], first[i + 1]);
  };
  std::int64_t too_far = n;
  if (team <= 1) {
    for (std::int64_t i = 0; i < n; ++i)
      if (!wrap(i)) too_far = std::min(too_far, i);
  } else {
#pragma omp parallel for schedule(static) num_threads(team) reduction(min : too_far)
    for (std::int64_t i = 0; i < n; ++i)
      if (!wrap(i)) too_far = std::min(too_far, i);
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
  const auto place = [&](std::int64_t i) {  // point i wrapped, then its images
    double* wrapped = images.xyz.data() + i * dims;
    for (int a = 0; a < dims; ++a)
      wrapped[a] = images.original[i * dims + a] - cells_along(&images.wraps[i * 3], frame, dims, a);
    const auto at = static_cast<std::size_t>(first[i]);
    write_images(wrapped, &fractional[i * 3], static_cast<point_id>(i), frame, reach,
                 images.xyz.data() + (points.size() + at) * dims, images.image_of.data() + at,
                 images.image_shift.data() + at * 3);
  };
  parallel_for_dynamic(n, team, place, 256);
  return images;
}

double image_margin(double extent, const CellProblem& problem) {
  double cell_extent = 0;
  for (int k = 0; k < problem.dims(); ++k)
    if (problem.frame.pbc[k]) cell_extent += problem.frame.scale * (2 + problem.cells_reach(k));
  return 0x1p-40 * (extent + cell_extent + problem.largest);
}

}  // namespace horizon::detail
