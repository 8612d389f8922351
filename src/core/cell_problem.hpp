#pragma once
// What the cell search and its oracle share: the checked problem (cell, horizons, rules) and
// the test and output of one entry (i, j, S), so that both decide and write every entry alike.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>

#include "cell_geometry.hpp"
#include "horizon/buffer.hpp"
#include "horizon/neighbor_list.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// One candidate entry: j's image at shift S, its vector D and the metric's accumulated distance.
struct CellEntry {
  point_id j = 0;
  std::int32_t shift[3] = {0, 0, 0};
  double vector[3] = {0, 0, 0};
  double accumulated = 0;
};

/// Order within a row: by j, then by shift, lexicographically.
HORIZON_HOST_DEVICE inline bool entry_before(const CellEntry& x, const CellEntry& y) {
  if (x.j != y.j) return x.j < y.j;
  for (int a = 0; a < 3; ++a)
    if (x.shift[a] != y.shift[a]) return x.shift[a] < y.shift[a];
  return false;
}

/// Whether entry (i, j, S) belongs in the list: not i itself at S = 0 unless asked for, and in
/// a half list only once per pair (i < j, or i = j and S "positive" or zero).
HORIZON_HOST_DEVICE inline bool keeps_entry(point_id i, point_id j, const std::int32_t* shift, bool half,
                                             bool self_interaction) {
  if (j != i) return !half || j > i;
  const bool zero = shift[0] == 0 && shift[1] == 0 && shift[2] == 0;
  if (zero) return self_interaction;
  return !half || positive_shift<3>(shift);
}

struct CellProblem {
  explicit CellProblem(const CellFrame& frame_) : frame(frame_) {}
  CellFrame frame;
  Metric metric = Metric::euclidean;
  bool half = false, self_interaction = false;
  PairOutputs outputs;
  double horizon = 0;  ///< without radii
  std::span<const double> radii;
  RadiusRule rule = RadiusRule::gather;
  double largest = 0;  ///< the largest horizon of any pair

  int dims() const { return frame.dims; }
  /// The threshold metric_accumulate() is compared with for the pair i, j.
  double threshold(std::size_t i, std::size_t j) const {
    return metric_threshold(metric, radii.empty() ? horizon : pair_radius(rule, radii[i], radii[j]));
  }
  /// The same for a pair whose radii are given (the distributed search holds them elsewhere).
  double threshold_of(double ri, double rj) const { return metric_threshold(metric, pair_radius(rule, ri, rj)); }
  /// How far (in cells, along periodic axis a) an image within the largest horizon can be: the
  /// metric's ball fits in the Euclidean one of radius largest (sqrt(dims) times it for Chebyshev).
  double cells_reach(int a) const {
    const double euclidean = metric == Metric::chebyshev ? largest * std::sqrt(double(dims())) : largest;
    return euclidean / frame.height[a];
  }
  /// Whether entry (i, j, S) belongs in the list (keeps_entry).
  bool keeps(point_id i, const CellEntry& e) const { return keeps_entry(i, e.j, e.shift, half, self_interaction); }
};

/// Checks `options` (and `radii`) for the cell path: Error naming the bad entry or combination.
/// `box` counts as an orthorhombic cell when `cell` has no periodic axis.
CellProblem cell_problem(PointView points, const SearchOptions& options, std::span<const double> radii,
                         RadiusRule rule);

/// f(dims, metric) with both as compile-time constants (std::integral_constant): the one place
/// the cell search and its oracle turn run-time dims and metric into template arguments.
template <class F>
decltype(auto) with_dims_and_metric(int dims, Metric metric, F&& f) {
  auto in = [&](auto d) -> decltype(auto) {
    switch (metric) {
      case Metric::manhattan: return f(d, std::integral_constant<Metric, Metric::manhattan>{});
      case Metric::chebyshev: return f(d, std::integral_constant<Metric, Metric::chebyshev>{});
      default: return f(d, std::integral_constant<Metric, Metric::euclidean>{});
    }
  };
  return dims == 3 ? in(std::integral_constant<int, 3>{}) : in(std::integral_constant<int, 2>{});
}

/// D and its accumulated distance for entry (i, j, S) of D-dimensional points.
template <int D, Metric M>
HORIZON_HOST_DEVICE inline void measure(const double* xi, const double* xj, const CellFrame& frame, CellEntry& e) {
  pair_vector<D>(xi, xj, e.shift, frame, e.vector);
  e.accumulated = metric_accumulate<M>(e.vector[0], e.vector[1], D == 3 ? e.vector[2] : 0.0);
}

/// The list's arrays, filled entry by entry at known positions.
struct CellEntries {
  int dims = 3;
  PairOutputs outputs;
  Metric metric = Metric::euclidean;
  Buffer<point_id> indices;
  Buffer<std::int32_t> shifts;
  Buffer<double> distances, vectors;

  CellEntries(std::size_t count, int dims_, PairOutputs outputs_, Metric metric_)
      : dims(dims_), outputs(outputs_), metric(metric_), indices(count),
        shifts(outputs.shifts ? count * static_cast<std::size_t>(dims) : 0), distances(outputs.distances ? count : 0),
        vectors(outputs.vectors ? count * static_cast<std::size_t>(dims) : 0) {}

  void write(std::size_t at, const CellEntry& e) {
    indices[at] = e.j;
    for (int a = 0; a < dims; ++a) {
      if (outputs.shifts) shifts[at * dims + a] = e.shift[a];
      if (outputs.vectors) vectors[at * dims + a] = e.vector[a];
    }
    if (outputs.distances)
      distances[at] = metric == Metric::euclidean ? std::sqrt(e.accumulated) : e.accumulated;
  }

  /// Entries [from, from + count) of `other` to [to, to + count).
  void copy(const CellEntries& other, std::size_t from, std::size_t to, std::size_t count) {
    const auto d = static_cast<std::size_t>(dims);
    std::copy_n(other.indices.data() + from, count, indices.data() + to);
    if (outputs.shifts) std::copy_n(other.shifts.data() + from * d, count * d, shifts.data() + to * d);
    if (outputs.distances) std::copy_n(other.distances.data() + from, count, distances.data() + to);
    if (outputs.vectors) std::copy_n(other.vectors.data() + from * d, count * d, vectors.data() + to * d);
  }

  NeighborList list(Buffer<std::int64_t> offsets, bool half) && {
    NeighborList result(std::move(offsets), std::move(indices), half);
    result.set_geometry(outputs, std::move(shifts), std::move(distances), std::move(vectors), dims);
    return result;
  }
};

}  // namespace horizon::detail
