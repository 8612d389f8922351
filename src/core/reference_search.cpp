#include "reference_search.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "../backends/backends.hpp"
#include "horizon/buffer.hpp"
#include "horizon/error.hpp"
#include "horizon/stopwatch.hpp"
#include "parallel_scan.hpp"
#include "periodic_images.hpp"

namespace horizon::detail {
namespace {

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

}  // namespace

void validate_box_shape(const SearchOptions& options, int dims) {
  const auto& box = options.box;
  for (int a = 0; a < 3; ++a) {
    if (!(std::isfinite(box[a]) && box[a] >= 0))
      throw Error(std::string("box: the period on axis ") + axis_name(a) + " must be finite and >= 0 (0: open)");
    if (box[a] > 0 && a >= dims)
      throw Error(std::string("box: a period on axis ") + axis_name(a) + " but the points are " +
                  std::to_string(dims) + "-D");
    if (box[a] > 0 && !(options.horizon < box[a] / 2))
      throw Error("box: the horizon " + std::to_string(options.horizon) + " must be below half the period (" +
                  std::to_string(box[a]) + " / 2) on axis " + axis_name(a));
  }
}

void throw_outside_box(const char* which, std::int64_t id, const double* xyz, int dims, const SearchOptions& options) {
  const auto& box = options.box;
  for (int a = 0; a < dims; ++a)
    if (box[a] > 0 && !(xyz[a] >= 0 && xyz[a] < box[a]))
      throw Error(std::string(which) + " " + std::to_string(id) + " has " + axis_name(a) + " = " +
                  std::to_string(xyz[a]) + ", outside the periodic box [0, " + std::to_string(box[a]) + ")");
}

namespace {

/// Point i's coordinates, as PeriodicBox reads them.
void coordinates_of(PointView points, std::size_t i, double* xyz) {
  for (int a = 0; a < points.dims(); ++a) xyz[a] = points(i, a);
}

}  // namespace

void validate_box(PointView points, const SearchOptions& options, const char* which,
                  const std::int64_t* ids, int threads) {
  validate_box_shape(options, points.dims());
  // The first point outside the box, on all threads; then its message.
  const PeriodicBox box(options, points.dims());
  const auto n = static_cast<std::int64_t>(points.size());
  std::int64_t outside = n;
#pragma omp parallel for schedule(static) reduction(min : outside) \
    num_threads(threads > 0 ? threads : omp_get_max_threads()) if (threads != 1 && n > (1 << 14))
  for (std::int64_t i = 0; i < n; ++i) {
    double xyz[3];
    coordinates_of(points, static_cast<std::size_t>(i), xyz);
    if (!box.contains(xyz)) outside = std::min(outside, i);
  }
  if (outside == n) return;
  double xyz[3];
  coordinates_of(points, static_cast<std::size_t>(outside), xyz);
  throw_outside_box(which, ids ? ids[outside] : outside, xyz, points.dims(), options);
}

namespace {

/// The points that have periodic images, ascending, and where their images start: point
/// which[k]'s are images first[k] to first[k + 1]. Only the points near a face are listed: a
/// count per point and its scan cost more than making the images (2-core Zen 3 VM, 10^6 points,
/// 12 % with images: 15 ms on one core).
struct ImagePlan {
  std::vector<std::int64_t> which;
  std::vector<std::int64_t> first{0};
  std::size_t count() const { return static_cast<std::size_t>(first.back()); }
};

/// Lists points [begin, end) of `xyz` (D coordinates each, type T) that have images, with
/// their image counts, and lowers `outside` to the first that lies outside the box.
template <int D, class T>
void plan_range(const T* xyz, const PeriodicBox& box, std::int64_t begin, std::int64_t end,
                std::vector<std::int64_t>& which, std::vector<int>& count, std::int64_t& outside) {
  // Images across the low face below below[a], across the high face from above[a] (as
  // PeriodicBox::axis_shifts). An open axis has neither (NaN compares false) and no bounds.
  double below[D], above[D];
  bool periodic[D];
  for (int a = 0; a < D; ++a) {
    periodic[a] = box.period[a] > 0;
    below[a] = periodic[a] ? box.reach[a] : std::numeric_limits<double>::quiet_NaN();
    above[a] = periodic[a] ? box.period[a] - box.reach[a] : std::numeric_limits<double>::quiet_NaN();
  }
  for (std::int64_t i = begin; i < end; ++i) {
    int images = 1;
    bool inside = true;
    for (int a = 0; a < D; ++a) {  // no branch: a point near a face is rare, and unpredictable
      const double x = static_cast<double>(xyz[i * D + a]);
      images *= 1 + (x < below[a]) + (x >= above[a]);
      inside &= (!periodic[a]) | ((x >= 0) & (x < box.period[a]));
    }
    if (!inside && i < outside) outside = i;
    if (images > 1) {
      which.push_back(i);
      count.push_back(images - 1);
    }
  }
}

/// The plan of `points`' images. With `check`, the points are validated against the box in
/// the same pass (validate_box's error).
ImagePlan plan_images(PointView points, const SearchOptions& options, int threads, bool check = false) {
  const auto n = static_cast<std::int64_t>(points.size());
  const PeriodicBox box(options, points.dims());
  if (n <= (1 << 14)) threads = 1;
  std::vector<std::vector<std::int64_t>> which(static_cast<std::size_t>(threads));
  std::vector<std::vector<int>> count(static_cast<std::size_t>(threads));
  std::int64_t outside = n;
#pragma omp parallel num_threads(threads) reduction(min : outside)
  {
    const int t = omp_get_thread_num(), used = omp_get_num_threads();
    const std::int64_t begin = n * t / used, end = n * (t + 1) / used;
    auto& w = which[static_cast<std::size_t>(t)];
    auto& c = count[static_cast<std::size_t>(t)];
    const bool three = points.dims() == 3;
    if (points.is_float32())
      (three ? plan_range<3, float> : plan_range<2, float>)(points.float32_data(), box, begin, end, w, c, outside);
    else
      (three ? plan_range<3, double> : plan_range<2, double>)(points.float64_data(), box, begin, end, w, c, outside);
  }
  if (check && outside < n) {
    double xyz[3];
    coordinates_of(points, static_cast<std::size_t>(outside), xyz);
    throw_outside_box("point", outside, xyz, points.dims(), options);
  }
  ImagePlan plan;
  for (std::size_t t = 0; t < which.size(); ++t) {
    plan.which.insert(plan.which.end(), which[t].begin(), which[t].end());
    for (const int images : count[t]) plan.first.push_back(plan.first.back() + images);
  }
  return plan;
}

/// Writes the images of `plan` at `xyz` and their originals' indices (+ `id_base`) at `id_of`,
/// in parallel.
void write_images(PointView points, const SearchOptions& options, const ImagePlan& plan, double* xyz, point_id* id_of,
                  point_id id_base, int threads) {
  const int dims = points.dims();
  const auto listed = static_cast<std::int64_t>(plan.which.size());
  const PeriodicBox box(options, dims);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1 && listed > (1 << 12))
  for (std::int64_t k = 0; k < listed; ++k) {
    const auto i = static_cast<std::size_t>(plan.which[static_cast<std::size_t>(k)]);
    const auto at = static_cast<std::size_t>(plan.first[static_cast<std::size_t>(k)]);
    double point[3], shift[26][3];
    coordinates_of(points, i, point);
    const int count = box.image_shifts(point, shift);
    for (int m = 0; m < count; ++m) {
      for (int a = 0; a < dims; ++a) xyz[(at + m) * dims + a] = point[a] + shift[m][a];
      id_of[at + m] = id_base + static_cast<point_id>(i);
    }
  }
}

}  // namespace

void append_images(PointView points, const SearchOptions& options, PointSet& local, std::vector<point_id>& id_of,
                   point_id id_base) {
  const int threads = omp_get_max_threads();
  const ImagePlan plan = plan_images(points, options, threads);
  const std::size_t before = id_of.size(), images = plan.count();
  local.xyz.resize(local.xyz.size() + images * static_cast<std::size_t>(points.dims()));
  id_of.resize(before + images);
  write_images(points, options, plan, local.xyz.data() + before * static_cast<std::size_t>(points.dims()),
               id_of.data() + before, id_base, threads);
}

namespace {

/// Points and the id each stands for (-1: none), in storage written once, in parallel, and not
/// zeroed first (on a VM each fresh page costs a fault: filling a vector, then growing it for
/// the images, cost more than the search).
struct LocalPoints {
  ScratchBuffer<double> xyz;
  ScratchBuffer<point_id> id_of;
  PointView view(int dims) const { return PointView(xyz.data(), id_of.size(), dims); }
};

/// The periodic images of `points` alone (ids: their originals' indices), the points checked
/// against the box in the same pass.
LocalPoints images_of(PointView points, const SearchOptions& options, int threads) {
  const ImagePlan plan = plan_images(points, options, threads, true);
  const std::size_t count = plan.count();
  LocalPoints images{ScratchBuffer<double>(count * static_cast<std::size_t>(points.dims())),
                     ScratchBuffer<point_id>(count)};
  write_images(points, options, plan, images.xyz.data(), images.id_of.data(), 0, threads);
  return images;
}

/// `sets` (each with the id of its first point, or -1 for "no id") one after another, then the
/// periodic images of the last set (ids as that set's) when options.box is periodic.
LocalPoints local_points(std::initializer_list<std::pair<PointView, point_id>> sets, const SearchOptions& options) {
  const PointView last = (sets.end() - 1)->first;
  const int dims = last.dims();
  const ImagePlan plan = is_periodic(options) ? plan_images(last, options, omp_get_max_threads()) : ImagePlan{};
  std::size_t total = plan.count();
  for (const auto& set : sets) total += set.first.size();
  if (total >= static_cast<std::size_t>(std::numeric_limits<point_id>::max()))
    throw Error("the points (queries, references and periodic images) must be fewer than 2^31 - 1");
  LocalPoints local{ScratchBuffer<double>(total * static_cast<std::size_t>(dims)), ScratchBuffer<point_id>(total)};
  std::size_t at = 0;
  for (const auto& [points, id] : sets) {
    const auto n = static_cast<std::int64_t>(points.size());
    double* const xyz = local.xyz.data() + at * static_cast<std::size_t>(dims);
    point_id* const ids = local.id_of.data() + at;
#pragma omp parallel for schedule(static) if (n > (1 << 14))
    for (std::int64_t i = 0; i < n; ++i) {
      for (int a = 0; a < dims; ++a) xyz[i * dims + a] = points(static_cast<std::size_t>(i), a);
      ids[i] = id < 0 ? -1 : id + static_cast<point_id>(i);
    }
    at += points.size();
  }
  if (is_periodic(options))
    write_images(last, options, plan, local.xyz.data() + at * static_cast<std::size_t>(dims), local.id_of.data() + at,
                 (sets.end() - 1)->second, omp_get_max_threads());
  return local;
}

}  // namespace

bool is_periodic(const SearchOptions& options) {
  return options.box[0] > 0 || options.box[1] > 0 || options.box[2] > 0;
}

NeighborList search_mapped(PointView local, std::size_t queries, const point_id* id_of,
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

NeighborList search_periodic(PointView points, Backend backend, const SearchOptions& options, SearchStats& stats) {
  if (options.queries != 0) throw Error("SearchOptions::queries cannot be combined with a periodic box");
  if (backend == Backend::cuda && options.devices.size() <= 1) {
    // One GPU checks the points against the box, makes the images and finds each as its
    // original: the host touches no point twice.
    validate_box_shape(options, points.dims());
    if (points.empty()) return NeighborList({0}, {}, options.half);
    SearchOptions one = options;
    if (!options.devices.empty()) one.device = options.devices[0];
    one.devices.clear();
    return search_cuda(points, one, stats);
  }
  Stopwatch clock;  // the grid's time covers the checks and images too
  const int threads = backend == Backend::serial ? 1 : options.threads > 0 ? options.threads : omp_get_max_threads();
  validate_box_shape(options, points.dims());
  if (points.empty()) return NeighborList({0}, {}, options.half);
  if (backend != Backend::cuda) {
    // The CPU backends sort the images into the cells after the points, each found as its
    // original: the rows come out final.
    const LocalPoints made = images_of(points, options, threads);
    const double images_seconds = clock.lap();
    SearchOptions inner = options;
    inner.box = {0, 0, 0};
    const Images images{made.view(points.dims()), made.id_of};
    NeighborList list = backend == Backend::serial ? search_serial(points, inner, stats, images)
                                                   : search_openmp(points, inner, stats, images);
    stats.grid_seconds += images_seconds;
    return list;
  }
  // Several GPUs: each part a query search among points and images, the ids mapped after.
  validate_box(points, options, "point", nullptr, threads);
  const LocalPoints local = local_points({{points, 0}}, options);
  NeighborList list =
      search_mapped(local.view(points.dims()), points.size(), local.id_of.data(), points.size(), options, stats);
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
  // Queries first (rows, dropped as ids), then the references (ids shifted down), then the
  // references' periodic images.
  const LocalPoints local = local_points({{queries, -1}, {references, 0}}, options);
  NeighborList list = search_mapped(local.view(queries.dims()), queries.size(), local.id_of.data(),
                                    queries.size() + references.size(), options, stats);
  stats.search_seconds = clock.lap() - stats.grid_seconds;
  return list;
}

}  // namespace horizon::detail
