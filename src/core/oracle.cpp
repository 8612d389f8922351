#include "horizon/oracle.hpp"

namespace horizon {

namespace {

bool neighbours(PointView points, std::size_t i, std::size_t j, Metric metric, double threshold) {
  const double dx = points(i, 0) - points(j, 0);
  const double dy = points(i, 1) - points(j, 1);
  const double dz = points.dims() == 3 ? points(i, 2) - points(j, 2) : 0.0;
  switch (metric) {
    case Metric::euclidean: return metric_accumulate<Metric::euclidean>(dx, dy, dz) < threshold;
    case Metric::manhattan: return metric_accumulate<Metric::manhattan>(dx, dy, dz) < threshold;
    case Metric::chebyshev: return metric_accumulate<Metric::chebyshev>(dx, dy, dz) < threshold;
  }
  return false;
}

}  // namespace

std::vector<point_id> brute_force_family(PointView points, std::size_t i,
                                         const SearchOptions& options) {
  const double threshold = metric_threshold(options.metric, options.horizon);
  std::vector<point_id> family;
  for (std::size_t j = options.half ? i + 1 : 0; j < points.size(); ++j)
    if (j != i && neighbours(points, i, j, options.metric, threshold))
      family.push_back(static_cast<point_id>(j));
  return family;
}

NeighborList brute_force(PointView points, const SearchOptions& options) {
  Buffer<std::int64_t> offsets{0};
  Buffer<point_id> indices;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (options.queries == 0 || i < options.queries) {  // the others are references only
      const auto family = brute_force_family(points, i, options);
      indices.insert(indices.end(), family.begin(), family.end());
    }
    offsets.push_back(static_cast<std::int64_t>(indices.size()));
  }
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

}  // namespace horizon
