#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include <omp.h>

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

namespace {

/// Whether any of v[begin, end) is NaN or infinite: a test of the exponent bits, which the
/// compiler vectorises (std::isfinite in the loop is not).
template <typename Float, typename Bits, Bits exponent>
bool any_non_finite(const Float* v, std::size_t begin, std::size_t end) {
  bool bad = false;
  for (std::size_t i = begin; i < end; ++i) {
    Bits bits;
    std::memcpy(&bits, v + i, sizeof(bits));
    bad |= (bits & exponent) == exponent;
  }
  return bad;
}

bool any_non_finite(PointView points, std::size_t begin, std::size_t end) {
  if (points.is_float32())
    return any_non_finite<float, std::uint32_t, 0x7f800000u>(points.float32_data(), begin, end);
  return any_non_finite<double, std::uint64_t, 0x7ff0000000000000ull>(points.float64_data(), begin, end);
}

}  // namespace

void detail::validate_point_shape(PointView points) {
  if (points.dims() != 2 && points.dims() != 3)
    throw Error("points must have 2 or 3 coordinates, not " + std::to_string(points.dims()));
  if (points.size() > static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error(std::to_string(points.size()) + " points: at most 2^31-1 per search");
}

void detail::validate_points(PointView points, int threads) {
  validate_point_shape(points);
  check_finite(points, threads);
}

void detail::check_finite(PointView points, int threads) {
  // Pieces tested on all cores (1.5 GB of coordinates at memory speed); the first bad piece
  // is then searched for its first bad value.
  constexpr std::size_t piece = std::size_t{1} << 16;
  const std::size_t values = points.size() * static_cast<std::size_t>(points.dims());
  const auto pieces = static_cast<std::int64_t>((values + piece - 1) / piece);
  std::int64_t first_bad = pieces;
  const auto bad = [&](std::int64_t p) {
    const std::size_t begin = static_cast<std::size_t>(p) * piece;
    return any_non_finite(points, begin, std::min(values, begin + piece));
  };
  const int team = threads > 0 ? threads : omp_get_max_threads();
  if (pieces <= 4 || team == 1) {  // no parallel region: even an inactive one costs a small search ~0.4 us
    for (std::int64_t p = 0; p < pieces && first_bad == pieces; ++p)
      if (bad(p)) first_bad = p;
  } else {
#pragma omp parallel for schedule(static) reduction(min : first_bad) num_threads(team)
    for (std::int64_t p = 0; p < pieces; ++p)
      if (bad(p)) first_bad = std::min(first_bad, p);
  }
  for (std::size_t at = static_cast<std::size_t>(first_bad) * piece; at < values; ++at) {
    const std::size_t i = at / static_cast<std::size_t>(points.dims());
    const int a = static_cast<int>(at % static_cast<std::size_t>(points.dims()));
    if (!std::isfinite(points(i, a)))
      throw Error("point " + std::to_string(i) + " has a non-finite coordinate (" + std::to_string(points(i, a)) + ")");
  }
}

void validate(PointView points) { detail::validate_points(points, 0); }

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
