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

/// The candidates still within the horizon, compared as the search compares them (row point
/// minus candidate, (dx*dx + dy*dy) + dz*dz or its l1/linf forms, against the threshold).
template <Metric M, int D>
NeighborList refresh_with(const NeighborList& candidates, const double* xyz, double horizon, int threads) {
  const double limit = metric_threshold(M, horizon);
  return detail::select_entries(
      candidates, [](std::size_t) { return false; },
      [&](std::size_t i, point_id j) {
        const double* a = xyz + D * i;
        const double* b = xyz + D * static_cast<std::size_t>(j);
        return metric_accumulate<M>(a[0] - b[0], a[1] - b[1], D == 3 ? a[2] - b[2] : 0.0) < limit;
      },
      threads);
}

template <Metric M>
NeighborList refresh_in(const NeighborList& candidates, const double* xyz, int dims, double horizon, int threads) {
  return dims == 3 ? refresh_with<M, 3>(candidates, xyz, horizon, threads)
                   : refresh_with<M, 2>(candidates, xyz, horizon, threads);
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
  std::vector<double> promoted;  // float32 input, as the search promotes it
  const double* xyz = points.float64_data();
  if (!xyz) {
    promoted.resize(built_at_.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      for (int a = 0; a < dims_; ++a) promoted[i * static_cast<std::size_t>(dims_) + a] = points(i, a);
    xyz = promoted.data();
  }
  const double h = options_.horizon;
  threads = resolve(threads);
  switch (options_.metric) {
    case Metric::manhattan: return refresh_in<Metric::manhattan>(candidates_, xyz, dims_, h, threads);
    case Metric::chebyshev: return refresh_in<Metric::chebyshev>(candidates_, xyz, dims_, h, threads);
    default: return refresh_in<Metric::euclidean>(candidates_, xyz, dims_, h, threads);
  }
}

}  // namespace horizon
