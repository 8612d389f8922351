#include "cell_search.hpp"

#include <hwy/contrib/sort/vqsort.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "cell_images.hpp"
#include "cell_problem.hpp"
#include "cell_walk.hpp"
#include "horizon/error.hpp"
#include "horizon/cell_index.hpp"
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
/// was kept, as in a full list almost always (the candidates differ only by rounding). With
/// `names` (the points were renumbered; tables.names), row p of the candidates is the caller's
/// row names[p], and its neighbours are written by the caller's ids.
template <int D, Metric M>
NeighborList map_rows(const NeighborList& candidates, const ImageTables& tables, const CellProblem& problem,
                      std::size_t points, int threads, const SearchOptions& options) {
  const auto rows = static_cast<std::int64_t>(points);
  const std::int64_t self = problem.self_interaction ? 1 : 0;
  const std::int64_t* room = candidates.offsets().data();  // where the caller's row i may go
  Buffer<std::int64_t> room_by_name;
  if (tables.names) {
    room_by_name = Buffer<std::int64_t>(points + 1);
    room_by_name[0] = 0;
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1 && rows > 4096)
    for (std::int64_t p = 0; p < rows; ++p) room_by_name[tables.names[p] + 1] = room[p + 1] - room[p];
    inclusive_scan(room_by_name.data() + 1, points, threads);
    room = room_by_name.data();
  }
  const auto capacity = static_cast<std::size_t>(room[points] + self * rows);
  const PairOutputs& out = problem.outputs;
  const std::size_t entry_bytes = sizeof(point_id) + (out.shifts ? D * sizeof(std::int32_t) : 0) +
                                  (out.distances ? sizeof(double) : 0) + (out.vectors ? D * sizeof(double) : 0);
  check_list_fits(static_cast<std::int64_t>(capacity), options, entry_bytes);
  CellEntries spacious(capacity, D, problem.outputs, problem.metric);
  Buffer<std::int64_t> offsets(points + 1);
  offsets[0] = 0;
  const auto threshold = [&](point_id i, point_id j) {
    return problem.threshold(static_cast<std::size_t>(tables.name(i)), static_cast<std::size_t>(tables.name(j)));
  };
  // Renumbered rows come in the renumbered order of j: sorted again by the caller's j (a stable
  // sort, so that each j's entries stay in the order of their shifts) when asked for.
  const bool sort_again = tables.names && options.sort_rows;
#pragma omp parallel num_threads(threads) if (threads > 1 && rows > 512)
  {
    std::vector<CellEntry> kept;
    std::vector<std::uint64_t> keys;
    std::optional<hwy::Sorter> sorter;  // its construction asks the kernel for random bytes
    if (sort_again) sorter.emplace();
#pragma omp for schedule(dynamic, 512)
    for (std::int64_t p = 0; p < rows; ++p) {
      const point_id i = tables.name(static_cast<point_id>(p));
      const auto first = static_cast<std::size_t>(room[i] + self * i);
      std::size_t at = first;
      const auto row = candidates.row(static_cast<std::size_t>(p));
      kept.clear();
      walk_row<D, M>(row.data(), row.size(), static_cast<point_id>(p), tables, problem.frame, threshold,
                     problem.half, problem.self_interaction, [&](CellEntry e, std::int64_t) {
                       e.j = tables.name(e.j);
                       if (sort_again) kept.push_back(e);
                       else spacious.write(at++, e);
                     });
      if (sort_again) {
        keys.resize(kept.size());
        for (std::size_t k = 0; k < kept.size(); ++k) keys[k] = std::uint64_t(std::uint32_t(kept[k].j)) << 32 | k;
        (*sorter)(keys.data(), keys.size(), hwy::SortAscending());
        for (const std::uint64_t key : keys) spacious.write(at++, kept[key & 0xffffffffu]);
      }
      offsets[i + 1] = static_cast<std::int64_t>(at - first);
    }
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

/// From this many points on, points in no spatial order are renumbered in the order of a
/// grid's cells, so that a row's candidates lie near each other in memory.
constexpr std::size_t renumber_from = std::size_t{1} << 15;

/// Whether the points are in no spatial order: more than half of a sample of consecutive pairs
/// lie over 8 horizons apart (a lattice, a supercell built cell by cell or atoms sorted by
/// cell have almost all of theirs within one or two).
bool scattered(PointView points, double horizon) {
  const std::size_t samples = std::min<std::size_t>(1024, points.size() - 1);
  const double far = 64 * horizon * horizon;
  std::size_t apart = 0;
  for (std::size_t s = 0; s < samples; ++s) {
    // Scattered over the ids (a regular stride can fall on a lattice's every row end).
    const std::size_t i = static_cast<std::size_t>((s * 0x9E3779B97F4A7C15ull) % (points.size() - 1));
    double d2 = 0;
    for (int a = 0; a < points.dims(); ++a) d2 += (points(i + 1, a) - points(i, a)) * (points(i + 1, a) - points(i, a));
    apart += d2 > far;
  }
  return 2 * apart > samples;
}

/// The points' ids in the order of the cells of a grid of side `horizon` (ascending ids within
/// a cell).
ScratchBuffer<point_id> cell_order(PointView points, double horizon, int threads) {
  const CellIndex index(points, Grid::fit(points, horizon, 1, threads), threads);
  return ScratchBuffer<point_id>(index.order().begin(), index.order().begin() + static_cast<std::ptrdiff_t>(points.size()));
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
  // Points in no spatial order make every candidate of the walk a cache miss (10^6 random
  // atoms, m = 3.015, ids, one core of the Zen 4 VM: 9.4-10.3 s against 1.2 s in cell order):
  // the search then works on the points renumbered in cell order, and sorts each row again by
  // the caller's ids if asked to (5.4 s; 1.9 s unsorted).
  ScratchBuffer<point_id> names;
  ScratchBuffer<double> renumbered;
  PointView searched = points;
  if (points.size() >= renumber_from && scattered(points, problem.largest)) {
    names = cell_order(points, problem.largest, threads);
    renumbered = ScratchBuffer<double>(points.size() * static_cast<std::size_t>(dims));
    const auto n = static_cast<std::int64_t>(points.size());
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
    for (std::int64_t p = 0; p < n; ++p)
      for (int a = 0; a < dims; ++a) renumbered[p * dims + a] = points(static_cast<std::size_t>(names[p]), a);
    searched = PointView(renumbered.data(), points.size(), dims);
  }
  const Images images = make_images(searched, problem, margin, threads);
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
    const ImageTables tables{images.original.data(), images.wraps.data(), images.image_of.data(),
                             images.image_shift.data(), points.size(), names.empty() ? nullptr : names.data()};
    return map_rows<decltype(d)::value, decltype(m)::value>(candidates, tables, problem, points.size(), threads, options);
  });
  stats.grid_seconds += images_seconds;
  stats.search_seconds += clock.lap();
  return list;
}

}  // namespace horizon::detail
