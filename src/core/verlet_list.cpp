#include "horizon/verlet_list.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "select_entries.hpp"
#include "horizon/error.hpp"
#include "horizon/metric.hpp"

namespace horizon {

namespace {

int resolve(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

template <Metric M>
double distance_measure(PointView points, std::size_t i, std::size_t j) {  // as the search compares it
  const double dz = points.dims() == 3 ? points(i, 2) - points(j, 2) : 0.0;
  return metric_accumulate<M>(points(i, 0) - points(j, 0), points(i, 1) - points(j, 1), dz);
}

template <Metric M>
NeighborList refresh_with(const NeighborList& candidates, PointView points, double horizon, int threads) {
  const double limit = metric_threshold(M, horizon);
  return detail::select_entries(
      candidates, [](std::size_t) { return false; },
      [&](std::size_t i, point_id j) { return distance_measure<M>(points, i, static_cast<std::size_t>(j)) < limit; },
      threads);
}

}  // namespace

VerletList::VerletList(PointView points, const SearchOptions& options, double skin)
    : options_(options), skin_(skin), dims_(points.dims()) {
  if (!(skin > 0) || !std::isfinite(skin)) throw Error("Verlet skin must be finite and > 0, not " + std::to_string(skin));
  if (options.box[0] > 0 || options.box[1] > 0 || options.box[2] > 0)
    throw Error("a Verlet list in a periodic box is not supported: points wrapping across it break the skin bound");
  SearchOptions wide = options;
  wide.horizon = options.horizon + skin;
  candidates_ = search(points, wide);  // validates the points and the horizon
  built_at_.resize(points.size() * static_cast<std::size_t>(dims_));
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int a = 0; a < dims_; ++a) built_at_[i * static_cast<std::size_t>(dims_) + a] = points(i, a);
}

void VerletList::check_shape(PointView points) const {
  if (points.dims() != dims_ || points.size() * static_cast<std::size_t>(dims_) != built_at_.size())
    throw Error("the Verlet list was built for " + std::to_string(built_at_.size() / static_cast<std::size_t>(dims_)) +
                " points in " + std::to_string(dims_) + "-D, not " + std::to_string(points.size()) + " in " +
                std::to_string(points.dims()) + "-D");
}

bool VerletList::needs_rebuild(PointView points, int threads) const {
  check_shape(points);
  validate(points);
  const PointView built(built_at_.data(), points.size(), dims_);
  // Less a margin far above the rounding of distances near the horizon (differences of close
  // coordinates are exact, so the error is relative to the distances, not the coordinates).
  const double half_skin = 0.5 * skin_ - 1e-9 * (options_.horizon + skin_);
  const auto n = static_cast<std::int64_t>(points.size());
  bool moved = false;
#pragma omp parallel for schedule(static) num_threads(resolve(threads)) reduction(|| : moved)
  for (std::int64_t i = 0; i < n; ++i) {
    double d[3] = {0, 0, 0};
    for (int a = 0; a < dims_; ++a) d[a] = points(static_cast<std::size_t>(i), a) - built(static_cast<std::size_t>(i), a);
    double step = 0;
    switch (options_.metric) {
      case Metric::euclidean: step = std::sqrt((d[0] * d[0] + d[1] * d[1]) + d[2] * d[2]); break;
      case Metric::manhattan: step = (std::abs(d[0]) + std::abs(d[1])) + std::abs(d[2]); break;
      case Metric::chebyshev: step = std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])}); break;
    }
    moved = moved || !(step < half_skin);
  }
  return moved;
}

NeighborList VerletList::refresh(PointView points, int threads) const {
  check_shape(points);
  validate(points);
  switch (options_.metric) {
    case Metric::manhattan: return refresh_with<Metric::manhattan>(candidates_, points, options_.horizon, resolve(threads));
    case Metric::chebyshev: return refresh_with<Metric::chebyshev>(candidates_, points, options_.horizon, resolve(threads));
    default: return refresh_with<Metric::euclidean>(candidates_, points, options_.horizon, resolve(threads));
  }
}

}  // namespace horizon
