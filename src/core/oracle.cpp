#include "horizon/oracle.hpp"

#include <algorithm>

#include "cell_search.hpp"
#include "horizon/radii.hpp"

namespace horizon {

namespace {

double accumulate(Metric metric, double dx, double dy, double dz) {
  switch (metric) {
    case Metric::euclidean: return metric_accumulate<Metric::euclidean>(dx, dy, dz);
    case Metric::manhattan: return metric_accumulate<Metric::manhattan>(dx, dy, dz);
    case Metric::chebyshev: return metric_accumulate<Metric::chebyshev>(dx, dy, dz);
  }
  return 0;
}

/// Whether point i of `a` and point j of `b` (or, in a periodic box, an image of j: its
/// coordinates shifted by -L, 0 or +L on each periodic axis, rounded to double) are closer
/// than the horizon.
bool neighbours(PointView a, std::size_t i, PointView b, std::size_t j, const SearchOptions& options) {
  const double threshold = metric_threshold(options.metric, options.horizon);
  const int dims = a.dims();
  int reach[3];  // the shifts tried per axis: -1..1 on periodic axes, 0 on open ones
  for (int axis = 0; axis < 3; ++axis) reach[axis] = axis < dims && options.box[static_cast<std::size_t>(axis)] > 0;
  for (int sx = -reach[0]; sx <= reach[0]; ++sx)
    for (int sy = -reach[1]; sy <= reach[1]; ++sy)
      for (int sz = -reach[2]; sz <= reach[2]; ++sz) {
        const int shift[3] = {sx, sy, sz};
        double d[3] = {0, 0, 0};
        for (int axis = 0; axis < dims; ++axis) {
          const double image = shift[axis] == 0 ? b(j, axis) : b(j, axis) + shift[axis] * options.box[static_cast<std::size_t>(axis)];
          d[axis] = a(i, axis) - image;
        }
        if (accumulate(options.metric, d[0], d[1], d[2]) < threshold) return true;
      }
  return false;
}

/// Row q: every reference within horizon_of(q) of query q (nothing excluded as self).
template <typename Horizon>
NeighborList query_rows(PointView queries, PointView references, const SearchOptions& options, Horizon horizon_of) {
  Buffer<std::int64_t> offsets{0};
  Buffer<point_id> indices;
  SearchOptions pair = options;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    pair.horizon = horizon_of(q);
    for (std::size_t r = 0; r < references.size(); ++r)
      if (neighbours(queries, q, references, r, pair)) indices.push_back(static_cast<point_id>(r));
    offsets.push_back(static_cast<std::int64_t>(indices.size()));
  }
  return NeighborList(std::move(offsets), std::move(indices), false);
}

}  // namespace

std::vector<point_id> brute_force_family(PointView points, std::size_t i,
                                         const SearchOptions& options) {
  std::vector<point_id> family;
  for (std::size_t j = options.half ? i + 1 : 0; j < points.size(); ++j)
    if (j != i && neighbours(points, i, points, j, options)) family.push_back(static_cast<point_id>(j));
  return family;
}

NeighborList brute_force(PointView points, const SearchOptions& options) {
  if (detail::needs_cell_search(options)) return detail::brute_force_cell(points, options, {}, RadiusRule::gather);
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

NeighborList brute_force(PointView queries, PointView references, const SearchOptions& options) {
  return query_rows(queries, references, options, [&](std::size_t) { return options.horizon; });
}

NeighborList brute_force_with_radii(PointView points, std::span<const double> radii, RadiusRule rule,
                                    const SearchOptions& options) {
  if (detail::needs_cell_search(options) || rule == RadiusRule::sum)
    return detail::brute_force_cell(points, options, radii, rule);
  Buffer<std::int64_t> offsets{0};
  Buffer<point_id> indices;
  SearchOptions pair = options;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = options.half ? i + 1 : 0; j < points.size(); ++j) {
      switch (rule) {
        case RadiusRule::gather: pair.horizon = radii[i]; break;
        case RadiusRule::scatter: pair.horizon = radii[j]; break;
        case RadiusRule::max: pair.horizon = std::max(radii[i], radii[j]); break;
        default: pair.horizon = pair_radius(rule, radii[i], radii[j]); break;
      }
      if (j != i && neighbours(points, i, points, j, pair)) indices.push_back(static_cast<point_id>(j));
    }
    offsets.push_back(static_cast<std::int64_t>(indices.size()));
  }
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

NeighborList brute_force_with_radii(PointView queries, std::span<const double> radii, PointView references,
                                    const SearchOptions& options) {
  return query_rows(queries, references, options, [&](std::size_t q) { return radii[q]; });
}

}  // namespace horizon
