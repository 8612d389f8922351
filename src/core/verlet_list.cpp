#include "horizon/verlet_list.hpp"

#include <omp.h>

#include <cmath>

#include "reference_search.hpp"
#include "select_entries.hpp"
#include "horizon/error.hpp"
#include "horizon/metric.hpp"

namespace horizon {

namespace {

int resolve(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

/// The candidates still within the horizon, compared as the search compares them (row point
/// minus candidate, metric_accumulate() against the threshold).
NeighborList refresh_from(const NeighborList& candidates, const double* xyz, int dims, Metric metric, double horizon,
                          int threads) {
  const double limit = metric_threshold(metric, horizon);
  return detail::select_marked(
      candidates,
      [&](std::size_t i, const point_id* ids, std::int64_t count, std::uint64_t* bits) {
        return detail::mark_within(metric, dims, xyz + dims * i, ids, count, xyz, limit, bits);
      },
      threads);
}

/// Whether a point of `now` is `limit` or farther (in the metric) from where it was `then`.
template <Metric M>
bool any_moved(PointView now, PointView then, double limit, int threads) {
  const double threshold = metric_threshold(M, limit);
  const auto n = static_cast<std::int64_t>(now.size());
  bool moved = false;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(|| : moved)
  for (std::int64_t p = 0; p < n; ++p) {
    const auto i = static_cast<std::size_t>(p);
    const double dz = now.dims() == 3 ? now(i, 2) - then(i, 2) : 0.0;
    moved = moved || !(metric_accumulate<M>(now(i, 0) - then(i, 0), now(i, 1) - then(i, 1), dz) < threshold);
  }
  return moved;
}

}  // namespace

VerletList::VerletList(PointView points, const SearchOptions& options, double skin)
    : options_(options), skin_(skin) {
  if (!(skin > 0) || !std::isfinite(skin)) throw Error("Verlet skin must be finite and > 0, not " + std::to_string(skin));
  if (detail::is_periodic(options))
    throw Error("a Verlet list in a periodic box is not supported: points wrapping across it break the skin bound");
  SearchOptions wide = options;
  wide.horizon = options.horizon + skin;
  candidates_ = search(points, wide);  // validates the points and the horizon
  built_at_ = to_point_set(points);
}

void VerletList::check_shape(PointView points) const {
  if (points.dims() != built_at_.dims || points.size() != built_at_.size())
    throw Error("the Verlet list was built for " + std::to_string(built_at_.size()) + " points in " +
                std::to_string(built_at_.dims) + "-D, not " + std::to_string(points.size()) + " in " +
                std::to_string(points.dims()) + "-D");
}

bool VerletList::needs_rebuild(PointView points, int threads) const {
  check_shape(points);
  validate(points);
  // Less a margin far above the rounding of distances near the horizon (differences of close
  // coordinates are exact, so the error is relative to the distances, not the coordinates).
  const double half_skin = 0.5 * skin_ - 1e-9 * (options_.horizon + skin_);
  const PointView then = built_at_.view();
  threads = resolve(threads);
  switch (options_.metric) {
    case Metric::manhattan: return any_moved<Metric::manhattan>(points, then, half_skin, threads);
    case Metric::chebyshev: return any_moved<Metric::chebyshev>(points, then, half_skin, threads);
    default: return any_moved<Metric::euclidean>(points, then, half_skin, threads);
  }
}

NeighborList VerletList::refresh(PointView points, int threads) const {
  check_shape(points);
  validate(points);
  PointSet promoted;  // float32 input, as the search promotes it
  const double* xyz = points.float64_data();
  if (!xyz) {
    promoted = to_point_set(points);
    xyz = promoted.xyz.data();
  }
  return refresh_from(candidates_, xyz, built_at_.dims, options_.metric, options_.horizon, resolve(threads));
}

}  // namespace horizon
