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

/// The images append_images writes, as offsets: point i's from first[i] to first[i + 1]. With
/// `check`, the points are validated against the box in the same pass (validate_box's error).
ScratchBuffer<std::int64_t> image_offsets(PointView points, const SearchOptions& options, int threads,
                                          bool check = false) {
  const auto n = static_cast<std::int64_t>(points.size());
  const PeriodicBox box(options, points.dims());
  ScratchBuffer<std::int64_t> first(points.size() + 1);
  first[0] = 0;
  std::int64_t outside = n;
#pragma omp parallel for schedule(static) reduction(min : outside) num_threads(threads) \
    if (threads > 1 && n > (1 << 14))
  for (std::int64_t i = 0; i < n; ++i) {
    double xyz[3];
    coordinates_of(points, static_cast<std::size_t>(i), xyz);
    first[static_cast<std::size_t>(i) + 1] = box.image_count(xyz);
    if (check && !box.contains(xyz)) outside = std::min(outside, i);
  }
  if (outside < n) {
    double xyz[3];
    coordinates_of(points, static_cast<std::size_t>(outside), xyz);
    throw_outside_box("point", outside, xyz, points.dims(), options);
  }
  inclusive_scan(first.data() + 1, points.size(), threads);
  return first;
}

/// Writes the images of image_offsets at `xyz` and their originals' indices (+ `id_base`) at
/// `id_of`, in parallel.
void write_images(PointView points, const SearchOptions& options, const ScratchBuffer<std::int64_t>& first,
                  double* xyz, point_id* id_of, point_id id_base, int threads) {
  const int dims = points.dims();
  const auto n = static_cast<std::int64_t>(points.size());
  const PeriodicBox box(options, dims);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1 && n > (1 << 14))
  for (std::int64_t i = 0; i < n; ++i) {
    const auto at = static_cast<std::size_t>(first[static_cast<std::size_t>(i)]);
    if (first[static_cast<std::size_t>(i) + 1] == first[static_cast<std::size_t>(i)]) continue;  // most points
    double point[3], shift[26][3];
    coordinates_of(points, static_cast<std::size_t>(i), point);
    const int count = box.image_shifts(point, shift);
    for (int k = 0; k < count; ++k) {
      for (int a = 0; a < dims; ++a) xyz[(at + k) * dims + a] = point[a] + shift[k][a];
      id_of[at + k] = id_base + static_cast<point_id>(i);
    }
  }
}

}  // namespace

void append_images(PointView points, const SearchOptions& options, PointSet& local, std::vector<point_id>& id_of,
                   point_id id_base) {
  const int threads = omp_get_max_threads();
  const ScratchBuffer<std::int64_t> first = image_offsets(points, options, threads);
  const std::size_t before = id_of.size(), images = static_cast<std::size_t>(first.back());
  local.xyz.resize(local.xyz.size() + images * static_cast<std::size_t>(points.dims()));
  id_of.resize(before + images);
  write_images(points, options, first, local.xyz.data() + before * static_cast<std::size_t>(points.dims()),
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
  const ScratchBuffer<std::int64_t> first = image_offsets(points, options, threads, true);
  const auto count = static_cast<std::size_t>(first.back());
  LocalPoints images{ScratchBuffer<double>(count * static_cast<std::size_t>(points.dims())),
                     ScratchBuffer<point_id>(count)};
  write_images(points, options, first, images.xyz.data(), images.id_of.data(), 0, threads);
  return images;
}

/// `sets` (each with the id of its first point, or -1 for "no id") one after another, then the
/// periodic images of the last set (ids as that set's) when options.box is periodic.
LocalPoints local_points(std::initializer_list<std::pair<PointView, point_id>> sets, const SearchOptions& options) {
  const PointView last = (sets.end() - 1)->first;
  const int dims = last.dims();
  const ScratchBuffer<std::int64_t> first =
      is_periodic(options) ? image_offsets(last, options, omp_get_max_threads()) : ScratchBuffer<std::int64_t>{0};
  std::size_t total = static_cast<std::size_t>(first.back());
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
    write_images(last, options, first, local.xyz.data() + at * static_cast<std::size_t>(dims), local.id_of.data() + at,
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
