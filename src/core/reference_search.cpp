#include "reference_search.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "horizon/error.hpp"
#include "horizon/stopwatch.hpp"
#include "parallel_scan.hpp"

namespace horizon::detail {
namespace {

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

}  // namespace

void validate_box(PointView points, const SearchOptions& options, const char* which,
                  const std::int64_t* ids) {
  const auto& box = options.box;
  for (int a = 0; a < 3; ++a) {
    if (!(std::isfinite(box[a]) && box[a] >= 0))
      throw Error(std::string("box: the period on axis ") + axis_name(a) + " must be finite and >= 0 (0: open)");
    if (box[a] > 0 && a >= points.dims())
      throw Error(std::string("box: a period on axis ") + axis_name(a) + " but the points are " +
                  std::to_string(points.dims()) + "-D");
    if (box[a] > 0 && !(options.horizon < box[a] / 2))
      throw Error("box: the horizon " + std::to_string(options.horizon) + " must be below half the period (" +
                  std::to_string(box[a]) + " / 2) on axis " + axis_name(a));
  }
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int a = 0; a < points.dims(); ++a) {
      const double x = points(i, a);
      if (box[a] > 0 && !(x >= 0 && x < box[a]))
        throw Error(std::string(which) + " " + std::to_string(ids ? ids[i] : static_cast<std::int64_t>(i)) + " has " + axis_name(a) + " = " +
                    std::to_string(x) + ", outside the periodic box [0, " + std::to_string(box[a]) + ")");
    }
}

void append_images(PointView points, const SearchOptions& options, PointSet& local, std::vector<point_id>& id_of,
                   point_id id_base) {
  const int dims = points.dims();
  for (std::size_t i = 0; i < points.size(); ++i) {
    double shifts[3][3];  // per axis: 0, then the shifts this point needs
    int count[3];
    for (int a = 0; a < 3; ++a) {
      const double period = options.box[a];
      shifts[a][0] = 0;
      count[a] = 1;
      if (a >= dims || period == 0) continue;
      // The margin keeps every image whose rounded coordinate could be within the horizon.
      const double reach = options.horizon + period * 0x1p-40;
      const double x = points(i, a);
      if (x < reach) shifts[a][count[a]++] = period;
      if (x >= period - reach) shifts[a][count[a]++] = -period;
    }
    for (int sx = 0; sx < count[0]; ++sx)
      for (int sy = 0; sy < count[1]; ++sy)
        for (int sz = 0; sz < count[2]; ++sz) {
          if (sx == 0 && sy == 0 && sz == 0) continue;
          const double shift[3] = {shifts[0][sx], shifts[1][sy], shifts[2][sz]};
          for (int a = 0; a < dims; ++a) local.xyz.push_back(points(i, a) + shift[a]);
          id_of.push_back(id_base + static_cast<point_id>(i));
        }
  }
}

bool is_periodic(const SearchOptions& options) {
  return options.box[0] > 0 || options.box[1] > 0 || options.box[2] > 0;
}

NeighborList search_mapped(PointView local, std::size_t queries, const std::vector<point_id>& id_of,
                           std::size_t ascending_below, const SearchOptions& options, SearchStats& stats) {
  if (queries == 0) return NeighborList({0}, {}, options.half);
  SearchOptions inner = options;
  inner.box = {0, 0, 0};
  inner.half = false;
  inner.queries = queries;
  const NeighborList list = search(local, inner, &stats);

  const auto rows = static_cast<std::int64_t>(queries);
  auto keeps = [&](point_id i, point_id j) { return id_of[j] >= 0 && (!options.half || id_of[j] > i); };
  Buffer<std::int64_t> offsets(queries + 1);
  offsets[0] = 0;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < rows; ++i) {
    const auto row = list.row(static_cast<std::size_t>(i));
    offsets[i + 1] = std::count_if(row.begin(), row.end(), [&](point_id j) { return keeps(static_cast<point_id>(i), j); });
  }
  inclusive_scan(offsets.data() + 1, queries, omp_get_max_threads());
  Buffer<point_id> indices(static_cast<std::size_t>(offsets[queries]));
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::int64_t i = 0; i < rows; ++i) {
    point_id* const out = indices.data() + offsets[i];
    point_id* at = out;
    point_id* unordered_from = nullptr;  // where the ids mapped out of order begin
    for (point_id j : list.row(static_cast<std::size_t>(i))) {
      if (!keeps(static_cast<point_id>(i), j)) continue;
      if (static_cast<std::size_t>(j) >= ascending_below && !unordered_from) unordered_from = at;
      *at++ = id_of[j];
    }
    // Sorted rows list the ascending part first: sort the rest and merge the two.
    if (options.sort_rows && unordered_from) {
      std::sort(unordered_from, at);
      std::inplace_merge(out, unordered_from, at);
    }
  }
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

NeighborList search_periodic(PointView points, const SearchOptions& options, SearchStats& stats) {
  if (options.queries != 0) throw Error("SearchOptions::queries cannot be combined with a periodic box");
  Stopwatch clock;  // the search's time covers the checks, images and mapping too
  validate_box(points, options, "point");
  PointSet local{points.dims(), std::vector<double>(points.size() * static_cast<std::size_t>(points.dims()))};
  copy_points(points, local, 0);
  std::vector<point_id> id_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) id_of[i] = static_cast<point_id>(i);
  append_images(points, options, local, id_of, 0);
  if (local.size() >= static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error("box: the points and their periodic images exceed 2^31 - 1");
  NeighborList list = search_mapped(local.view(), points.size(), id_of, points.size(), options, stats);
  stats.search_seconds = clock.lap() - stats.grid_seconds;
  return list;
}

NeighborList search_references(PointView queries, PointView references, const SearchOptions& options,
                               SearchStats& stats) {
  if (queries.dims() != references.dims())
    throw Error("queries are " + std::to_string(queries.dims()) + "-D but references " +
                std::to_string(references.dims()) + "-D");
  if (options.half) throw Error("half lists are for one point set, not queries against references");
  if (options.queries != 0) throw Error("SearchOptions::queries is for one point set, not queries against references");
  Stopwatch clock;  // the search's time covers the checks, copies, images and mapping too
  if (is_periodic(options)) {
    validate_box(queries, options, "query point");
    validate_box(references, options, "reference point");
  }
  const std::size_t total = queries.size() + references.size();
  if (total >= static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error("queries and references together must be fewer than 2^31 - 1 points");
  // Queries first (rows, dropped as ids), then the references (ids shifted down), then the
  // references' periodic images.
  PointSet local{queries.dims(), std::vector<double>(total * static_cast<std::size_t>(queries.dims()))};
  copy_points(queries, local, 0);
  copy_points(references, local, queries.size());
  std::vector<point_id> id_of(total, -1);
  for (std::size_t r = 0; r < references.size(); ++r) id_of[queries.size() + r] = static_cast<point_id>(r);
  if (is_periodic(options)) append_images(references, options, local, id_of, 0);
  if (local.size() >= static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error("box: the points and their periodic images exceed 2^31 - 1");
  NeighborList list = search_mapped(local.view(), queries.size(), id_of, total, options, stats);
  stats.search_seconds = clock.lap() - stats.grid_seconds;
  return list;
}

}  // namespace horizon::detail
