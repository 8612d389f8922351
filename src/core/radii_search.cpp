#include "horizon/radii.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include <omp.h>

#include "../backends/backends.hpp"
#include "backend_choice.hpp"
#include "cell_search.hpp"
#include "family_search.hpp"
#include "parallel_scan.hpp"
#include "radius_checks.hpp"
#include "transpose_rows.hpp"
#include "horizon/cell_index.hpp"
#include "horizon/error.hpp"
#include "horizon/grid.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon {

RadiusRule parse_radius_rule(const std::string& name) {
  if (name == "gather") return RadiusRule::gather;
  if (name == "scatter") return RadiusRule::scatter;
  if (name == "max") return RadiusRule::max;
  if (name == "min") return RadiusRule::min;
  if (name == "sum") return RadiusRule::sum;
  throw Error("unknown radius rule '" + name + "' (expected gather, scatter, max, min or sum)");
}

const char* radius_rule_name(RadiusRule rule) {
  switch (rule) {
    case RadiusRule::gather: return "gather";
    case RadiusRule::scatter: return "scatter";
    case RadiusRule::max: return "max";
    case RadiusRule::min: return "min";
    case RadiusRule::sum: return "sum";
  }
  return "?";
}

void detail::check_radii(std::size_t count, std::span<const double> radii, RadiusRule rule, bool half,
                         const std::string& one, const std::string& many) {
  if (radii.size() != count)
    throw Error("radii: " + std::to_string(radii.size()) + " radii for " + std::to_string(count) + " " + many);
  for (std::size_t i = 0; i < radii.size(); ++i)
    if (!(std::isfinite(radii[i]) && radii[i] > 0))
      throw Error("radii: " + one + " " + std::to_string(i) + " has radius " + std::to_string(radii[i]) +
                  " (each must be finite and > 0)");
  if (half && (rule == RadiusRule::gather || rule == RadiusRule::scatter))
    throw Error(std::string("radii: a half list needs a symmetric rule (max or min) or sum; with ") +
                radius_rule_name(rule) + " d(i, j) < r_i does not imply d(j, i) < r_j");
}

namespace {

/// `one` and `many` name what carries the radii: point(s) or quer(y|ies).
void validate_radii(PointView points, std::span<const double> radii, RadiusRule rule, const SearchOptions& options,
                    const std::string& one = "point", const std::string& many = "points") {
  detail::check_radii(points.size(), radii, rule, options.half, one, many);
  if (options.queries != 0) throw Error("radii: SearchOptions::queries is not supported with per-point radii");
  const double largest = radii.empty() ? 0 : *std::max_element(radii.begin(), radii.end());
  for (int a = 0; a < 3; ++a)
    if (options.box[static_cast<std::size_t>(a)] > 0 && !(largest < options.box[static_cast<std::size_t>(a)] / 2))
      throw Error("radii: the largest radius " + std::to_string(largest) + " must be below half the period (" +
                  std::to_string(options.box[static_cast<std::size_t>(a)]) + " / 2) on axis " + "xyz"[a]);
}

/// The metric's accumulated distance of points i and j, each axis's difference the smallest
/// over the periodic images of j (x_j, x_j + L, x_j - L, rounded, as the search tests them).
/// The accumulation grows with each |difference|, so this is the nearest image's.
template <Metric M>
double accumulated(PointView rows, std::size_t i, PointView ids, std::size_t j, const std::array<double, 3>& box) {
  double d[3] = {0, 0, 0};
  for (int a = 0; a < rows.dims(); ++a) {
    const double xi = rows(i, a), xj = ids(j, a);
    double nearest = std::fabs(xi - xj);
    if (box[static_cast<std::size_t>(a)] > 0) {
      const double period = box[static_cast<std::size_t>(a)];
      nearest = std::min({nearest, std::fabs(xi - (xj + period)), std::fabs(xi - (xj - period))});
    }
    d[a] = nearest;
  }
  return metric_accumulate<M>(d[0], d[1], d[2]);
}

/// A list in CSR form under construction.
struct Rows {
  Buffer<std::int64_t> offsets;
  Buffer<point_id> ids;
};

constexpr int most_classes = 31;
/// Radii within a factor 4 of their class's largest. Each class costs a grid over all points,
/// and its smaller radii reach more cells per neighbour; on the clustered cloud with radii
/// spanning 10x (horizon_radii_bench, gather, 2-core Zen 5 VM, rows tested in the cells they
/// reach) classes of a factor 4 took 1.3-1.4 s serially, a factor 2 2.5 s and 8 3.0 s: a finer
/// class brings a grid of mostly empty cells.
constexpr int class_bits = 2;

/// The class of radius r: class c holds the radii in (largest / 4^(c+1), largest / 4^c] (past
/// 30 classes, the rest in the last).
int class_of_radius(double r, double largest) {
  int c = 0;
  while (c + 1 < most_classes && r <= std::ldexp(largest, -class_bits * (c + 1))) ++c;
  return c;
}

/// The points of each radius class, ids ascending.
std::vector<std::vector<point_id>> radius_classes(std::span<const double> radii) {
  const double largest = *std::max_element(radii.begin(), radii.end());
  std::vector<std::vector<point_id>> members(most_classes);
  for (std::size_t i = 0; i < radii.size(); ++i)
    members[static_cast<std::size_t>(class_of_radius(radii[i], largest))].push_back(static_cast<point_id>(i));
  return members;
}

/// The gather rows on the CPU: per class, a grid at the class's largest radius, each row tested
/// with its point's radius (FamilyPass::row_radius) in the cells that radius reaches; every
/// class counted into one offsets array and filled into one list. With `min_rule`, the min
/// rule's full rows instead: each pair also below the candidate's radius.
Rows gather_on_cpu(PointView points, std::span<const double> radii, const SearchOptions& options, int threads,
                   SearchStats& stats, bool min_rule = false) {
  const std::size_t n = points.size();
  SearchOptions part = options;  // the classes' passes: full sorted rows within the largest radius
  part.horizon = *std::max_element(radii.begin(), radii.end());
  part.half = false;
  part.sort_rows = true;
  detail::validate_search(points, part);
  // Each point's class and each class's largest radius, on every thread (serial steps cost
  // as much as the search on 16 cores).
  const double largest = part.horizon;
  const auto count = static_cast<std::int64_t>(n);
  ScratchBuffer<std::uint8_t> class_of(n);
  double class_largest[most_classes] = {};
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1) reduction(max : class_largest[:most_classes])
  for (std::int64_t i = 0; i < count; ++i) {
    const double r = radii[static_cast<std::size_t>(i)];
    const int c = class_of_radius(r, largest);
    class_of[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(c);
    class_largest[c] = std::max(class_largest[c], r);
  }
  std::vector<std::unique_ptr<CellIndex>> indexes;
  std::vector<ScratchBuffer<double>> row_radius;  // per class, by sorted position: the members' radii, 0 elsewhere
  std::vector<ScratchBuffer<double>> own_threshold;  // min rule, per class, by sorted position: every point's
  std::vector<detail::RadiusClass> classes;
  Stopwatch clock;
  for (int c = 0; c < most_classes; ++c) {
    if (!(class_largest[c] > 0)) continue;  // no member
    const CellIndex& index = *indexes.emplace_back(std::make_unique<CellIndex>(
        points, Grid::fit(points, class_largest[c], part.cells_per_horizon, threads), threads));
    ScratchBuffer<double>& radius = row_radius.emplace_back(n);
    const point_id* order = index.order().data();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
    for (std::int64_t p = 0; p < count; ++p) {
      const auto i = static_cast<std::size_t>(order[p]);
      radius[static_cast<std::size_t>(p)] = class_of[i] == c ? radii[i] : 0.0;
    }
    classes.push_back({&index, radius.data()});
    if (min_rule) {
      ScratchBuffer<double>& limit = own_threshold.emplace_back(n + CellIndex::padding, 0.0);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
      for (std::int64_t p = 0; p < count; ++p)
        limit[static_cast<std::size_t>(p)] = metric_threshold(options.metric, radii[static_cast<std::size_t>(order[p])]);
      classes.back().candidate_threshold = limit.data();
    }
  }
  stats.grid_seconds += clock.lap();
  auto [offsets, ids] = detail::search_radius_classes(classes, part, threads).release();
  stats.search_seconds += clock.lap();
  stats.backend = threads > 1 || options.backend == Backend::openmp ? Backend::openmp : Backend::serial;
  stats.threads = threads;
  return Rows{std::move(offsets), std::move(ids)};
}

/// Row i (a point of `row_points`): every j of `id_points` with d(i, j) < radii[i] (the gather
/// rule), j != i when both are the same point set; the candidates come from one query search
/// per radius class (any backend, periodic boxes).
template <Metric M>
Rows gather(PointView row_points, std::span<const double> radii, PointView id_points, bool same_set,
            const SearchOptions& options, int threads, SearchStats& stats) {
  const std::size_t n = row_points.size();
  const std::vector<std::vector<point_id>> members = radius_classes(radii);
  Buffer<std::int64_t> count(n + 1, 0);
  std::vector<std::vector<point_id>> kept(most_classes);  // each class's rows, in member order
  for (int c = 0; c < most_classes; ++c) {
    const std::vector<point_id>& member = members[static_cast<std::size_t>(c)];
    if (member.empty()) continue;
    PointSet class_queries{row_points.dims(), {}};
    class_queries.xyz.reserve(member.size() * static_cast<std::size_t>(row_points.dims()));
    double reach = 0;
    for (const point_id i : member) {
      for (int a = 0; a < row_points.dims(); ++a) class_queries.xyz.push_back(row_points(static_cast<std::size_t>(i), a));
      reach = std::max(reach, radii[static_cast<std::size_t>(i)]);
    }
    SearchOptions class_options = options;
    class_options.horizon = reach;
    class_options.half = false;
    class_options.sort_rows = true;
    SearchStats class_stats;
    const NeighborList candidates = search(class_queries.view(), id_points, class_options, &class_stats);
    stats.grid_seconds += class_stats.grid_seconds;
    stats.search_seconds += class_stats.search_seconds;
    stats.backend = class_stats.backend;
    stats.threads = class_stats.threads;

    // Keep flags first, then the kept ids packed: each row's place is known after a scan.
    Stopwatch clock;
    std::vector<char> keep(static_cast<std::size_t>(candidates.total()));
    const auto rows = static_cast<std::int64_t>(member.size());
    std::vector<std::int64_t> start(member.size() + 1, 0);
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads) if (threads > 1)
    for (std::int64_t q = 0; q < rows; ++q) {
      const auto i = static_cast<std::size_t>(member[static_cast<std::size_t>(q)]);
      const double threshold = metric_threshold(M, radii[i]);
      std::int64_t found = 0;
      for (std::int64_t e = candidates.offsets()[q]; e < candidates.offsets()[q + 1]; ++e) {
        const auto j = static_cast<std::size_t>(candidates.indices()[e]);
        const bool near = (!same_set || j != i) && accumulated<M>(row_points, i, id_points, j, options.box) < threshold;
        keep[static_cast<std::size_t>(e)] = near;
        found += near;
      }
      start[static_cast<std::size_t>(q) + 1] = found;
      count[i + 1] = found;
    }
    for (std::size_t q = 0; q < member.size(); ++q) start[q + 1] += start[q];
    std::vector<point_id>& ids = kept[static_cast<std::size_t>(c)];
    ids.resize(static_cast<std::size_t>(start.back()));
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads) if (threads > 1)
    for (std::int64_t q = 0; q < rows; ++q) {
      std::int64_t out = start[static_cast<std::size_t>(q)];
      for (std::int64_t e = candidates.offsets()[q]; e < candidates.offsets()[q + 1]; ++e)
        if (keep[static_cast<std::size_t>(e)]) ids[static_cast<std::size_t>(out++)] = candidates.indices()[e];
    }
    stats.search_seconds += clock.lap();
  }

  // Rows in input order.
  Stopwatch clock;
  Rows out;
  out.offsets = std::move(count);
  for (std::size_t i = 0; i < n; ++i) out.offsets[i + 1] += out.offsets[i];
  out.ids.resize(static_cast<std::size_t>(out.offsets[n]));
  for (int c = 0; c < most_classes; ++c) {
    const std::vector<point_id>& member = members[static_cast<std::size_t>(c)];
    const std::vector<point_id>& ids = kept[static_cast<std::size_t>(c)];
    std::size_t from = 0;
    for (const point_id i : member) {
      const auto length = static_cast<std::size_t>(out.offsets[static_cast<std::size_t>(i) + 1] -
                                                   out.offsets[static_cast<std::size_t>(i)]);
      std::copy_n(ids.begin() + static_cast<std::ptrdiff_t>(from), length,
                  out.ids.begin() + out.offsets[static_cast<std::size_t>(i)]);
      from += length;
    }
  }
  stats.search_seconds += clock.lap();
  return out;
}

/// Row j of the transpose holds every i whose row holds j, ascending.
Rows transpose(const Rows& rows, int threads) {
  Rows out;
  detail::transpose_rows(rows.offsets.data(), rows.ids.data(), static_cast<std::int64_t>(rows.offsets.size()) - 1,
                         threads, out.offsets, out.ids);
  return out;
}

/// The union (Unite) or intersection of two ascending rows of distinct ids, written to `out`
/// when Write; returns its length. The union takes no branch on the ids: std::set_union's
/// compare mispredicted about every other id of rows whose ids interleave at random.
template <bool Unite, bool Write>
std::int64_t merge_rows(const point_id* a, const point_id* a_end, const point_id* b, const point_id* b_end,
                        point_id* out) {
  std::int64_t k = 0;
  while (a < a_end && b < b_end) {
    const point_id x = *a, y = *b;
    if constexpr (Unite) {
      if constexpr (Write) out[k] = std::min(x, y);
      ++k;
    } else if (x == y) {  // nothing written past the row's end: the next row may be another thread's
      if constexpr (Write) out[k] = x;
      ++k;
    }
    a += x <= y;
    b += y <= x;
  }
  if constexpr (Unite) {
    if constexpr (Write) {
      out = std::copy(a, a_end, out + k);
      std::copy(b, b_end, out);
    }
    k += (a_end - a) + (b_end - b);
  }
  return k;
}

/// Row i: the union (max) or intersection (min) of the sorted rows i of a and b; with `half`,
/// only ids above i. On several threads sized by a counting pass, then written in place, rows
/// in parallel; on one, appended in one pass (the counting pass would double its time).
Rows combine(const Rows& a, const Rows& b, bool unite, bool half, int threads) {
  const auto n = static_cast<std::int64_t>(a.offsets.size()) - 1;
  auto row_of = [](const Rows& r, std::int64_t i, bool above_only) {
    const point_id* first = r.ids.data() + r.offsets[static_cast<std::size_t>(i)];
    const point_id* last = r.ids.data() + r.offsets[static_cast<std::size_t>(i) + 1];
    return std::pair{above_only ? std::upper_bound(first, last, static_cast<point_id>(i)) : first, last};
  };
  auto merge = [&](std::int64_t i, point_id* out) {
    const auto [fa, la] = row_of(a, i, half);
    const auto [fb, lb] = row_of(b, i, half);
    if (unite) return out ? merge_rows<true, true>(fa, la, fb, lb, out) : merge_rows<true, false>(fa, la, fb, lb, out);
    return out ? merge_rows<false, true>(fa, la, fb, lb, out) : merge_rows<false, false>(fa, la, fb, lb, out);
  };
  Rows out;
  out.offsets.resize(static_cast<std::size_t>(n) + 1);
  out.offsets[0] = 0;
  if (threads <= 1) {
    out.ids.resize(unite ? a.ids.size() + b.ids.size() : std::min(a.ids.size(), b.ids.size()));
    for (std::int64_t i = 0; i < n; ++i)
      out.offsets[static_cast<std::size_t>(i) + 1] =
          out.offsets[static_cast<std::size_t>(i)] + merge(i, out.ids.data() + out.offsets[static_cast<std::size_t>(i)]);
    out.ids.resize(static_cast<std::size_t>(out.offsets[static_cast<std::size_t>(n)]));
    return out;
  }
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) out.offsets[static_cast<std::size_t>(i) + 1] = merge(i, nullptr);
  detail::inclusive_scan(out.offsets.data(), out.offsets.size(), threads);
  out.ids.resize(static_cast<std::size_t>(out.offsets[static_cast<std::size_t>(n)]));
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) merge(i, out.ids.data() + out.offsets[static_cast<std::size_t>(i)]);
  return out;
}

Backend effective_backend(const SearchOptions& options) {
  return options.backend == Backend::automatic && !backend_available(Backend::cuda) ? Backend::openmp : options.backend;
}

/// Threads of the filtering steps: one for the serial backend, else the search's.
int filter_threads(const SearchOptions& options) {
  return effective_backend(options) == Backend::serial ? 1 : options.threads > 0 ? options.threads : omp_get_max_threads();
}

/// Each sorted row i of a symmetric list less the ids up to i: its half list.
Rows upper_half(const Rows& rows, int threads) {
  const auto n = static_cast<std::int64_t>(rows.offsets.size()) - 1;
  auto above = [&](std::int64_t i) {
    const point_id* first = rows.ids.data() + rows.offsets[static_cast<std::size_t>(i)];
    const point_id* last = rows.ids.data() + rows.offsets[static_cast<std::size_t>(i) + 1];
    return std::pair{std::upper_bound(first, last, static_cast<point_id>(i)), last};
  };
  Rows out;
  out.offsets.resize(rows.offsets.size());
  out.offsets[0] = 0;
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto [first, last] = above(i);
    out.offsets[static_cast<std::size_t>(i) + 1] = last - first;
  }
  detail::inclusive_scan(out.offsets.data(), out.offsets.size(), threads);
  out.ids.resize(static_cast<std::size_t>(out.offsets.back()));
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto [first, last] = above(i);
    std::copy(first, last, out.ids.begin() + out.offsets[static_cast<std::size_t>(i)]);
  }
  return out;
}

template <Metric M>
Rows search_rows(PointView points, std::span<const double> radii, RadiusRule rule, const SearchOptions& options,
                 SearchStats& stats) {
  // The CPU backends test each row with its own radius inside the search; the GPU and periodic
  // boxes filter the rows of query searches.
  const Backend backend = effective_backend(options);
  const bool periodic = options.box[0] > 0 || options.box[1] > 0 || options.box[2] > 0;
  const int threads = filter_threads(options);
  const bool on_cpu = (backend == Backend::serial || backend == Backend::openmp) && !periodic;
  // Min rows straight from the search (d < min(r_i, r_j) is within r_i), halved after.
  if (on_cpu && rule == RadiusRule::min) {
    Rows rows = gather_on_cpu(points, radii, options, threads, stats, true);
    if (!options.half) return rows;
    Stopwatch clock;
    rows = upper_half(rows, threads);
    stats.search_seconds += clock.lap();
    return rows;
  }
  Rows gathered = on_cpu ? gather_on_cpu(points, radii, options, threads, stats)
                         : gather<M>(points, radii, points, true, options, threads, stats);
  if (rule == RadiusRule::gather) return gathered;
  Stopwatch clock;
  Rows scattered = transpose(gathered, threads);
  if (rule != RadiusRule::scatter) scattered = combine(gathered, scattered, rule == RadiusRule::max, options.half, threads);
  stats.search_seconds += clock.lap();
  return scattered;
}

}  // namespace

NeighborList search_with_radii(PointView queries, std::span<const double> radii, PointView references,
                               const SearchOptions& options, SearchStats* stats) {
  if (options.half) throw Error("radii: half lists are about one point set, not queries against references");
  validate_radii(queries, radii, RadiusRule::gather, options, "query", "queries");
  SearchStats local;
  SearchStats& out = stats ? *stats : local;
  out = SearchStats{};
  if (queries.empty()) return NeighborList(Buffer<std::int64_t>{0}, Buffer<point_id>{}, false);
  const int threads = filter_threads(options);
  Rows rows;
  switch (options.metric) {
    case Metric::euclidean: rows = gather<Metric::euclidean>(queries, radii, references, false, options, threads, out); break;
    case Metric::manhattan: rows = gather<Metric::manhattan>(queries, radii, references, false, options, threads, out); break;
    case Metric::chebyshev: rows = gather<Metric::chebyshev>(queries, radii, references, false, options, threads, out); break;
  }
  return NeighborList(std::move(rows.offsets), std::move(rows.ids), false);
}

NeighborList search_with_radii(PointView points, std::span<const double> radii, RadiusRule rule,
                               const SearchOptions& options, SearchStats* stats) {
  if (detail::needs_cell_search(options) || rule == RadiusRule::sum) {
    // Atomistic radii (ASE's r_i + r_j) and cells: each pair tested once with its own radius.
    detail::validate_points(points, 0);
    const detail::BackendChoice choice = detail::choose_backend(points.size(), options);
    SearchOptions chosen = options;
    chosen.backend = choice.backend;
    chosen.threads = choice.threads;
    if (points.empty()) chosen.horizon = 1;  // no radii to take it from: any valid horizon
    SearchStats local;
    SearchStats& out = stats ? *stats : local;
    out = SearchStats{};
    const NeighborList list = detail::search_cell(points, chosen, radii, rule, out);
    out.backend = choice.backend;
    out.threads = choice.threads;
    out.choice = choice.reason;
    return list;
  }
  validate_radii(points, radii, rule, options);
  SearchStats local;
  SearchStats& out = stats ? *stats : local;
  out = SearchStats{};
  if (points.empty()) return NeighborList(Buffer<std::int64_t>{0}, Buffer<point_id>{}, options.half);
  Rows rows;
  switch (options.metric) {
    case Metric::euclidean: rows = search_rows<Metric::euclidean>(points, radii, rule, options, out); break;
    case Metric::manhattan: rows = search_rows<Metric::manhattan>(points, radii, rule, options, out); break;
    case Metric::chebyshev: rows = search_rows<Metric::chebyshev>(points, radii, rule, options, out); break;
  }
  return NeighborList(std::move(rows.offsets), std::move(rows.ids), options.half);
}

}  // namespace horizon
