#include <cmath>
#include <limits>
#include <string>

#include "horizon/error.hpp"
#include "horizon/metric.hpp"
#include "horizon/points.hpp"

namespace horizon {

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
