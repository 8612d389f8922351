#include <cmath>
#include <limits>
#include <string>

#include "horizon/error.hpp"
#include "horizon/metric.hpp"
#include "horizon/points.hpp"

namespace horizon {

void copy_points(PointView points, PointSet& into, std::size_t at) {
  const int dims = points.dims();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(points.size()); ++i)
    for (int a = 0; a < dims; ++a)
      into.xyz[(at + static_cast<std::size_t>(i)) * dims + a] = points(static_cast<std::size_t>(i), a);
}

PointSet to_point_set(PointView points) {
  PointSet set{points.dims(), std::vector<double>(points.size() * static_cast<std::size_t>(points.dims()))};
  copy_points(points, set);
  return set;
}

void validate(PointView points) {
  if (points.dims() != 2 && points.dims() != 3)
    throw Error("points must have 2 or 3 coordinates, not " + std::to_string(points.dims()));
  if (points.size() > static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error(std::to_string(points.size()) + " points: at most 2^31-1 per search");
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int a = 0; a < points.dims(); ++a)
      if (!std::isfinite(points(i, a)))
        throw Error("point " + std::to_string(i) + " has a non-finite coordinate (" +
                    std::to_string(points(i, a)) + ")");
}

Metric parse_metric(const std::string& name) {
  if (name == "l2" || name == "euclidean") return Metric::euclidean;
  if (name == "l1" || name == "manhattan") return Metric::manhattan;
  if (name == "linf" || name == "chebyshev") return Metric::chebyshev;
  throw Error("unknown metric '" + name + "' (expected l2, l1 or linf)");
}

const char* metric_name(Metric metric) {
  switch (metric) {
    case Metric::euclidean: return "l2";
    case Metric::manhattan: return "l1";
    case Metric::chebyshev: return "linf";
  }
  return "?";
}

}  // namespace horizon
