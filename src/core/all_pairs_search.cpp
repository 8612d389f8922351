// The serial backend's search of a few points: every pair tested, no grid. Below a few dozen
// points the grid's arrays and passes cost more than all the pairs do (all_pairs_points).
#include "all_pairs_search.hpp"

#include <bit>
#include <cstdint>

#include "horizon/metric.hpp"
#include "memory_check.hpp"

namespace horizon::detail {

namespace {

/// near[i]: bit j set when points i and j are neighbours (the oracle's arithmetic, pair by pair).
template <Metric M>
void mark_neighbours(const double (*xyz)[3], std::size_t n, double threshold, std::uint64_t* near) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double d = metric_accumulate<M>(xyz[i][0] - xyz[j][0], xyz[i][1] - xyz[j][1], xyz[i][2] - xyz[j][2]);
      if (d < threshold) {
        near[i] |= std::uint64_t{1} << j;
        near[j] |= std::uint64_t{1} << i;
      }
    }
}

}  // namespace

bool all_pairs_searchable(PointView points, const SearchOptions& options, const Images& images) {
  return points.size() <= all_pairs_points && images.points.empty() && options.queries == 0;
}

NeighborList search_all_pairs(PointView points, const SearchOptions& options) {
  const std::size_t n = points.size();
  double xyz[all_pairs_points][3] = {};
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < points.dims(); ++a) xyz[i][a] = points(i, a);
  std::uint64_t near[all_pairs_points] = {};
  const double threshold = metric_threshold(options.metric, options.horizon);
  switch (options.metric) {
    case Metric::euclidean: mark_neighbours<Metric::euclidean>(xyz, n, threshold, near); break;
    case Metric::manhattan: mark_neighbours<Metric::manhattan>(xyz, n, threshold, near); break;
    case Metric::chebyshev: mark_neighbours<Metric::chebyshev>(xyz, n, threshold, near); break;
  }
  if (options.half)  // j > i only
    for (std::size_t i = 0; i < n; ++i) near[i] &= i + 1 < 64 ? ~std::uint64_t{0} << (i + 1) : 0;
  Buffer<std::int64_t> offsets(n + 1);
  offsets[0] = 0;
  for (std::size_t i = 0; i < n; ++i) offsets[i + 1] = offsets[i] + std::popcount(near[i]);
  check_list_fits(offsets[n], options);
  Buffer<point_id> indices(static_cast<std::size_t>(offsets[n]));
  point_id* out = indices.data();
  for (std::size_t i = 0; i < n; ++i)  // ascending j: rows come sorted
    for (std::uint64_t bits = near[i]; bits; bits &= bits - 1) *out++ = static_cast<point_id>(std::countr_zero(bits));
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

}  // namespace horizon::detail
