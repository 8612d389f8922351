#include "cell_search.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cell_images.hpp"
#include "cell_problem.hpp"
#include "cell_walk.hpp"
#include "horizon/error.hpp"
#include "horizon/grid.hpp"
#include "horizon/stopwatch.hpp"
#include "memory_check.hpp"
#include "parallel_scan.hpp"
#include "radius_checks.hpp"

namespace horizon::detail {

bool needs_cell_search(const SearchOptions& options) {
  return options.cell.periodic() || options.outputs.any() || options.self_interaction;
}

CellProblem cell_problem(PointView points, const SearchOptions& options, std::span<const double> radii,
                         RadiusRule rule) {
  const bool box = options.box[0] > 0 || options.box[1] > 0 || options.box[2] > 0;
  if (box && options.cell.periodic()) throw Error("cell: give either a box or a cell, not both");
  if (options.queries != 0) throw Error("cell: SearchOptions::queries cannot be combined with a cell or outputs");
  CellProblem problem(CellFrame(box ? Cell::orthorhombic(options.box) : options.cell, points.dims()));
  problem.metric = options.metric;
  problem.half = options.half;
  problem.self_interaction = options.self_interaction;
  problem.outputs = options.outputs;
  problem.horizon = options.horizon;
  problem.radii = radii;
  problem.rule = rule;
  if (radii.empty()) {
    validate_horizon(options.horizon, options.cells_per_horizon);
    problem.largest = options.horizon;
  } else {
    check_radii(points.size(), radii, rule, options.half);
    const double r = *std::max_element(radii.begin(), radii.end());
    problem.largest = rule == RadiusRule::sum ? 2 * r : r;
  }
  return problem;
}

namespace {

/// Above this many pair tests (queries x points and images) the engine's grid is cheaper.
constexpr std::size_t small_problem_tests = std::size_t{1} << 15;

/// The candidates of a small system: each of the first `queries` points against every other
/// point of `local`, rows ascending, with the engine's test (metric, horizon). The distances of
/// a row are computed in one loop the compiler vectorises, then compared.
template <int D, Metric M>
NeighborList all_candidates(PointView local, std::size_t queries, double horizon) {
  const double threshold = metric_threshold(M, horizon);
  const double* x = local.float64_data();
  const std::size_t n = local.size();
  std::vector<double> accumulated(n);
  Buffer<std::int64_t> offsets(queries + 1);
  offsets[0] = 0;
  std::vector<point_id> indices;
  for (std::size_t i = 0; i < queries; ++i) {
    const double* xi = x + i * D;
    for (std::size_t k = 0; k < n; ++k) {
      const double* xk = x + k * D;
      accumulated[k] = metric_accumulate<M>(xi[0] - xk[0], xi[1] - xk[1], D == 3 ? xi[2] - xk[2] : 0.0);
    }
    accumulated[i] = threshold;  // not itself
    for (std::size_t k = 0; k < n; ++k)
      if (accumulated[k] < threshold) indices.push_back(static_cast<point_id>(k));
    offsets[i + 1] = static_cast<std::int64_t>(indices.size());
  }
  return NeighborList(std::move(offsets), Buffer<point_id>(indices.begin(), indices.end()), false);
}

/// The list from the candidates, each row walked once: written where the candidates' row was
/// (with room for i itself under self_interaction), then moved together unless every candidate
/// was kept, as in a full list almost always (the candidates differ only by rounding).
template <int D, Metric M>
NeighborList map_rows(const NeighborList& candidates, const Images& images, const CellProblem& problem,
                      std::size_t points, int threads, const SearchOptions& options) {
  const auto rows = static_cast<std::int64_t>(points);
  const std::int64_t self = problem.self_interaction ? 1 : 0;
  const Buffer<std::int64_t>& room = candidates.offsets();
  const auto capacity = static_cast<std::size_t>(room[points] + self * rows);
  const PairOutputs& out = problem.outputs;
  const std::size_t entry_bytes = sizeof(point_id) + (out.shifts ? D * sizeof(std::int32_t) : 0) +
                                  (out.distances ? sizeof(double) : 0) + (out.vectors ? D * sizeof(double) : 0);
  // Reading /proc/meminfo costs ~20 us, more than a small cell's whole search: large lists only.
  if (options.max_memory > 0 || capacity * entry_bytes >= (std::size_t{64} << 20))
    check_list_fits(static_cast<std::int64_t>(capacity), options, entry_bytes);
  CellEntries spacious(capacity, D, problem.outputs, problem.metric);
  Buffer<std::int64_t> offsets(points + 1);
  offsets[0] = 0;
  const ImageTables tables{images.original.data(), images.wraps.data(), images.image_of.data(),
                           images.image_shift.data(), points};
  const auto threshold = [&](point_id i, point_id j) {
    return problem.threshold(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
  };
#pragma omp parallel for schedule(dynamic, 512) num_threads(threads) if (threads > 1 && rows > 512)
  for (std::int64_t i = 0; i < rows; ++i) {
    const auto first = static_cast<std::size_t>(room[i] + self * i);
    std::size_t at = first;
    const auto row = candidates.row(static_cast<std::size_t>(i));
    walk_row<D, M>(row.data(), row.size(), static_cast<point_id>(i), tables, problem.frame, threshold, problem.half,
                   problem.self_interaction, [&](const CellEntry& e) { spacious.write(at++, e); });
    offsets[i + 1] = static_cast<std::int64_t>(at - first);
  }
  inclusive_scan(offsets.data() + 1, points, threads);
  const auto total = static_cast<std::size_t>(offsets[points]);
  if (total == capacity) return std::move(spacious).list(std::move(offsets), problem.half);
  CellEntries exact(total, D, problem.outputs, problem.metric);
#pragma omp parallel for schedule(dynamic, 512) num_threads(threads) if (threads > 1 && rows > 512)
  for (std::int64_t i = 0; i < rows; ++i)
    exact.copy(spacious, static_cast<std::size_t>(room[i] + self * i), static_cast<std::size_t>(offsets[i]),
               static_cast<std::size_t>(offsets[i + 1] - offsets[i]));
  return std::move(exact).list(std::move(offsets), problem.half);
}

}  // namespace

NeighborList search_cell(PointView points, const SearchOptions& options, std::span<const double> radii,
                         RadiusRule rule, SearchStats& stats) {
  Stopwatch clock;
  const CellProblem problem = cell_problem(points, options, radii, rule);
  const int threads = options.backend == Backend::serial ? 1 : std::max(1, options.threads);
  const int dims = points.dims();
  if (points.empty()) {
    CellEntries none(0, dims, problem.outputs, problem.metric);
    return std::move(none).list(Buffer<std::int64_t>{0}, options.half);
  }
  // The engine's horizon covers the rounding of wrapped and image coordinates.
  double extent = problem.largest;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int a = 0; a < dims; ++a) extent = std::max(extent, std::fabs(points(i, a)));
  const double margin = image_margin(extent, problem);
  const Images images = make_images(points, problem, margin, threads);
  const double images_seconds = clock.lap();

  SearchOptions inner = options;
  inner.horizon = problem.largest + margin;
  inner.half = false;
  inner.sort_rows = true;
  inner.queries = points.size();
  inner.box = {0, 0, 0};
  inner.cell = Cell{};
  inner.outputs = PairOutputs{};
  inner.self_interaction = false;
  const PointView local(images.xyz.data(), images.xyz.size() / static_cast<std::size_t>(dims), dims);
  // A small system (a primitive cell) tests every query against every point and image at once:
  // cheaper than a grid, as the engine's fixed cost dominates a few hundred pair tests.
  const bool small = points.size() * local.size() <= small_problem_tests;
  const auto all_against_all = [&](auto d, auto m) {
    return all_candidates<decltype(d)::value, decltype(m)::value>(local, points.size(), inner.horizon);
  };
  const NeighborList candidates =
      small ? with_dims_and_metric(dims, inner.metric, all_against_all) : search(local, inner, &stats);
  if (small) {
    stats.backend = Backend::serial;
    stats.threads = 1;
  }
  clock.lap();

  NeighborList list = with_dims_and_metric(dims, problem.metric, [&](auto d, auto m) {
    return map_rows<decltype(d)::value, decltype(m)::value>(candidates, images, problem, points.size(), threads, options);
  });
  stats.grid_seconds += images_seconds;
  stats.search_seconds += clock.lap();
  return list;
}

}  // namespace horizon::detail
