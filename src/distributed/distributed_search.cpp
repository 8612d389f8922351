// The distributed search: preprocess (global bounds) -> decompose and migrate -> exchange
// ghosts -> search locally -> rows of owned points with global ids.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <optional>

#include "../core/cell_search.hpp"
#include "../core/memory_check.hpp"
#include "../core/partitioned_search.hpp"
#include "../core/reference_search.hpp"
#include "distributed_cell_search.hpp"
#include "exchange.hpp"
#include "horizon/distributed.hpp"
#include "horizon/error.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon {

Exchange parse_exchange(const std::string& name) {
  if (name == "thesis") return Exchange::thesis;
  if (name == "halo") return Exchange::halo;
  if (name == "overlap") return Exchange::overlap;
  throw Error("unknown exchange '" + name + "' (expected thesis, halo or overlap)");
}

const char* exchange_name(Exchange exchange) {
  switch (exchange) {
    case Exchange::thesis: return "thesis";
    case Exchange::halo: return "halo";
    case Exchange::overlap: return "overlap";
  }
  return "?";
}

namespace {

using detail::pack;
using detail::Packed;

struct Rank {
  MPI_Comm comm;
  int id, size;
};

// Whether a packed point is a reference (every point, without a query set): only references
// travel as ghosts. Periodic images carry -(id + 1).
bool is_reference(const Packed& p, std::int64_t first_query) {
  const double id = p[3] < 0 ? -p[3] - 1 : p[3];
  return first_query < 0 || id < static_cast<double>(first_query);
}

Bounds global_bounds(const Rank& rank, PointView points) {
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  if (!points.empty()) {
    const Bounds mine = bounds_of(points);
    lo = mine.lo;
    hi = mine.hi;
  }
  Bounds box;
  MPI_Allreduce(lo.data(), box.lo.data(), 3, MPI_DOUBLE, MPI_MIN, rank.comm);
  MPI_Allreduce(hi.data(), box.hi.data(), 3, MPI_DOUBLE, MPI_MAX, rank.comm);
  for (int a = points.dims(); a < 3; ++a) box.lo[a] = box.hi[a] = 0;
  return box;
}

// Every rank contributes every k-th point it holds to a sample of at most ~2^16 points that
// all ranks then hold, so all of them cut the same recursive bisection.
PointSet gather_sample(const Rank& rank, PointView points, std::size_t global_count, bool everyone_has_all) {
  const std::size_t stride = std::max<std::size_t>(1, global_count / 65536);
  PointSet sample{points.dims(), {}};
  for (std::size_t i = 0; i < points.size(); i += stride)
    for (int a = 0; a < points.dims(); ++a) sample.xyz.push_back(points(i, a));
  if (everyone_has_all) return sample;
  const int mine = static_cast<int>(sample.xyz.size());
  std::vector<int> counts(static_cast<std::size_t>(rank.size)), displs(static_cast<std::size_t>(rank.size));
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, rank.comm);
  std::exclusive_scan(counts.begin(), counts.end(), displs.begin(), 0);
  PointSet all{points.dims(), std::vector<double>(static_cast<std::size_t>(displs.back() + counts.back()))};
  MPI_Allgatherv(sample.xyz.data(), mine, MPI_DOUBLE, all.xyz.data(), counts.data(), displs.data(), MPI_DOUBLE,
                 rank.comm);
  return all;
}

Decomposition decompose(const Rank& rank, PointView points, std::size_t global_count, const Bounds& box,
                        Decomposition::Kind kind, bool everyone_has_all) {
  if (kind == Decomposition::Kind::brick) return Decomposition::brick(box, points.dims(), rank.size);
  const PointSet sample = gather_sample(rank, points, global_count, everyone_has_all);
  return Decomposition::rcb(box, sample.view(), rank.size);
}

// thesis §4.3/§4.5: cells of side horizon over the global box; each rank learns every rank's
// occupied cells and sends each of them the points it holds in cells adjacent to those.
std::vector<Packed> thesis_ghosts(const Rank& rank, const std::vector<Packed>& held, const Bounds& box,
                                  int dims, std::size_t global_count, double horizon, int width,
                                  std::int64_t first_query, detail::Traffic& traffic) {
  const Grid grid = Grid::from_bounds(box, dims, global_count, horizon, 1);
  using Cell = std::array<std::int64_t, 3>;
  auto cell_of = [&](const Packed& p) {
    Cell c{0, 0, 0};
    for (int a = 0; a < dims; ++a) c[static_cast<std::size_t>(a)] = grid.cell_of(p[static_cast<std::size_t>(a)], a);
    return c;
  };
  std::vector<Cell> mine;
  for (const Packed& p : held) mine.push_back(cell_of(p));
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());

  const int count = static_cast<int>(mine.size() * 3);
  std::vector<int> counts(static_cast<std::size_t>(rank.size)), displs(static_cast<std::size_t>(rank.size));
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, rank.comm);
  std::exclusive_scan(counts.begin(), counts.end(), displs.begin(), 0);
  std::vector<std::int64_t> all(static_cast<std::size_t>(displs.back() + counts.back()));
  MPI_Allgatherv(mine.data(), count, MPI_INT64_T, all.data(), counts.data(), displs.data(), MPI_INT64_T, rank.comm);
  traffic.bytes += static_cast<std::int64_t>(count) * 8 * (rank.size - 1);
  traffic.messages += rank.size - 1;

  std::vector<std::vector<Packed>> outgoing(static_cast<std::size_t>(rank.size));
  const int reach_z = dims == 3 ? 1 : 0;
  for (int r = 0; r < rank.size; ++r) {
    if (r == rank.id) continue;
    const Cell* first = reinterpret_cast<const Cell*>(all.data() + displs[static_cast<std::size_t>(r)]);
    const Cell* last = first + counts[static_cast<std::size_t>(r)] / 3;
    for (const Packed& p : held) {
      if (!is_reference(p, first_query)) continue;
      const Cell c = cell_of(p);
      bool adjacent = false;
      for (std::int64_t dz = -reach_z; dz <= reach_z && !adjacent; ++dz)
        for (std::int64_t dy = -1; dy <= 1 && !adjacent; ++dy)
          for (std::int64_t dx = -1; dx <= 1 && !adjacent; ++dx)
            adjacent = std::binary_search(first, last, Cell{c[0] + dx, c[1] + dy, c[2] + dz});
      if (adjacent) outgoing[static_cast<std::size_t>(r)].push_back(p);
    }
  }
  return detail::exchange_all(rank.comm, outgoing, width, traffic);
}

// Ghosts from spatial neighbours only, over a graph communicator of halo partners.
std::vector<Packed> halo_ghosts(const Rank& rank, const std::vector<Packed>& owned, const Decomposition& d,
                                int dims, double reach, int width, std::int64_t first_query,
                                detail::Traffic& traffic) {
  const std::vector<int> partners = d.partners(rank.id, reach);
  const int degree = static_cast<int>(partners.size());
  MPI_Comm graph;
  MPI_Dist_graph_create_adjacent(rank.comm, degree, partners.data(), MPI_UNWEIGHTED, degree, partners.data(),
                                 MPI_UNWEIGHTED, MPI_INFO_NULL, 0, &graph);
  std::vector<std::vector<Packed>> outgoing(partners.size());
  for (const Packed& p : owned)
    for (std::size_t k = 0; k < partners.size() && is_reference(p, first_query); ++k)
      if (d.box(partners[k]).near(p.data(), dims, reach)) outgoing[k].push_back(p);
  std::vector<Packed> ghosts = detail::exchange_with(graph, outgoing, width, traffic);
  MPI_Comm_free(&graph);
  return ghosts;
}

// The rows of the owned queries (after the owned references in `owned`, both by id) among the
// owned references and the ghosts, in global query and reference ids.
OwnedRows query_rows(const std::vector<Packed>& owned, const std::vector<Packed>& ghosts, int dims,
                     const SearchOptions& options, bool with_radii, std::int64_t first_query) {
  const auto queries_from =
      std::find_if(owned.begin(), owned.end(), [&](const Packed& p) { return !is_reference(p, first_query); });
  PointSet queries{dims, {}}, references{dims, {}};
  std::vector<double> radii;
  std::vector<point_id> global;
  OwnedRows out;
  for (auto p = queries_from; p != owned.end(); ++p) {
    for (int a = 0; a < dims; ++a) queries.xyz.push_back((*p)[static_cast<std::size_t>(a)]);
    out.ids.push_back(static_cast<std::int64_t>((*p)[3]) - first_query);
    radii.push_back((*p)[4]);
  }
  const auto owned_references = static_cast<std::size_t>(queries_from - owned.begin());
  for (const std::vector<Packed>* set : std::initializer_list<const std::vector<Packed>*>{&owned, &ghosts})
    for (const Packed& p : *set)
      if (is_reference(p, first_query)) {
        for (int a = 0; a < dims; ++a) references.xyz.push_back(p[static_cast<std::size_t>(a)]);
        global.push_back(static_cast<point_id>(p[3]));
      }
  SearchOptions local_options = options;
  local_options.box = {0, 0, 0};  // the images are among the ghosts
  if (out.ids.empty()) {
    out.rows = NeighborList({0}, {}, false);
    return out;
  }
  const NeighborList list = with_radii ? search_with_radii(queries.view(), radii, references.view(), local_options)
                                       : search(queries.view(), references.view(), local_options);
  out.rows = detail::rows_in_global_ids(list, global, out.ids.size(), false, options.sort_rows, owned_references);
  return out;
}

// Searches owned + ghosts on this node; only owned points get rows, in global ids. Owned points
// come first and ghosts after, each run ordered by global id (rows_in_global_ids merges them).
// With `rule`, each point is searched with the radius it carries. With a query set (ids from
// first_query on) only the owned queries get rows, among the references, owned and ghosts.
OwnedRows search_owned(std::vector<Packed>& owned, std::vector<Packed>& ghosts, int dims,
                       const SearchOptions& options, const std::optional<RadiusRule>& rule,
                       std::int64_t first_query) {
  // Periodic images (negative ids) get no row: they join the ghosts under their original's id.
  const auto image = [](const Packed& p) { return p[3] < 0; };
  std::copy_if(owned.begin(), owned.end(), std::back_inserter(ghosts), image);
  owned.erase(std::remove_if(owned.begin(), owned.end(), image), owned.end());
  for (Packed& p : ghosts)
    if (image(p)) p[3] = -p[3] - 1;
  const auto by_id = [](const Packed& a, const Packed& b) { return a[3] < b[3]; };
  std::sort(owned.begin(), owned.end(), by_id);
  std::sort(ghosts.begin(), ghosts.end(), by_id);
  if (first_query >= 0) return query_rows(owned, ghosts, dims, options, rule.has_value(), first_query);
  PointSet local{dims, {}};
  local.xyz.reserve((owned.size() + ghosts.size()) * static_cast<std::size_t>(dims));
  std::vector<point_id> global;
  global.reserve(owned.size() + ghosts.size());
  std::vector<double> radii;
  for (const std::vector<Packed>* set : std::initializer_list<const std::vector<Packed>*>{&owned, &ghosts})
    for (const Packed& p : *set) {
      for (int a = 0; a < dims; ++a) local.xyz.push_back(p[static_cast<std::size_t>(a)]);
      global.push_back(static_cast<point_id>(p[3]));
      if (rule) radii.push_back(p[4]);
    }
  SearchOptions local_options = options;
  local_options.half = false;  // a half list by local ids is not one by global ids
  local_options.box = {0, 0, 0};  // the images are among the ghosts
  local_options.queries = owned.size();
  OwnedRows out;
  if (owned.empty()) {
    out.rows = NeighborList({0}, {}, options.half);
    return out;
  }
  // With radii every local point gets a row (the ghosts' rows are dropped below).
  if (rule) local_options.queries = 0;
  const NeighborList list =
      rule ? search_with_radii(local.view(), radii, *rule, local_options) : search(local.view(), local_options);
  out.ids.assign(global.begin(), global.begin() + static_cast<std::ptrdiff_t>(owned.size()));
  out.rows = detail::rows_in_global_ids(list, global, owned.size(), options.half, options.sort_rows);
  return out;
}

// Radii: each finite and > 0 (naming the point's global id), a symmetric rule for half lists,
// the largest of all ranks below half of each period. Returns that largest radius, the reach.
double largest_radius(MPI_Comm comm, PointView points, const std::vector<std::int64_t>& ids,
                      std::span<const double> radii, RadiusRule rule, const SearchOptions& options,
                      const std::string& what = "point") {
  if (radii.size() != points.size())
    throw Error("radii: " + std::to_string(radii.size()) + " radii for " + std::to_string(points.size()) + " " +
                what + "s");
  double mine = 0, largest = 0;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    if (!(std::isfinite(radii[i]) && radii[i] > 0))
      throw Error("radii: " + what + " " + std::to_string(ids.empty() ? static_cast<std::int64_t>(i) : ids[i]) +
                  " has radius " + std::to_string(radii[i]) + " (each must be finite and > 0)");
    mine = std::max(mine, radii[i]);
  }
  if (options.half && (rule == RadiusRule::gather || rule == RadiusRule::scatter))
    throw Error(std::string("radii: a half list needs a symmetric rule (max or min), not ") + radius_rule_name(rule));
  MPI_Allreduce(&mine, &largest, 1, MPI_DOUBLE, MPI_MAX, comm);
  for (int a = 0; a < 3; ++a)
    if (options.box[static_cast<std::size_t>(a)] > 0 && !(largest < options.box[static_cast<std::size_t>(a)] / 2))
      throw Error("radii: the largest radius " + std::to_string(largest) + " must be below half the period (" +
                  std::to_string(options.box[static_cast<std::size_t>(a)]) + " / 2) on axis " + "xyz"[a]);
  return largest > 0 ? largest : 1.0;  // no points anywhere: any horizon will do
}

// The distributed search of `points` (ids, and radii with a rule, as held by this rank; the
// horizon is the reach: the largest radius with radii). With first_query >= 0, the points with
// ids from there on are queries (rows only) and the others references (entries only).
OwnedRows distributed_rows(MPI_Comm comm, PointView points, const std::vector<std::int64_t>& ids,
                           std::span<const double> radii, const std::optional<RadiusRule>& rule,
                           std::size_t global_count, const DistributedOptions& options, DistributedStats* stats,
                           std::int64_t first_query = -1) {
  Rank rank{comm, 0, 1};
  MPI_Comm_rank(comm, &rank.id);
  MPI_Comm_size(comm, &rank.size);
  validate(points);
  const bool everyone_has_all = options.exchange == Exchange::overlap;
  if (!everyone_has_all && ids.size() != points.size())
    throw Error("search_distributed: " + std::to_string(points.size()) + " points but " +
                std::to_string(ids.size()) + " global ids");
  const int width = rule ? 5 : 4;  // with radii the ghosts carry their own
  validate_horizon(options.search.horizon, options.search.cells_per_horizon);
  const int dims = points.dims();
  // A periodic box: each rank adds the images of the points it holds (those within the horizon
  // of a periodic face, shifted across it) as points of their own that get no row, with id
  // -(original + 1); from there the exchanges treat them as any point, and the local search
  // finds each pair at its nearest image.
  PointSet extended{dims, {}};
  std::vector<std::int64_t> extended_ids;
  std::vector<double> extended_radii;
  if (detail::is_periodic(options.search)) {
    detail::validate_box(points, options.search, "point", ids.empty() ? nullptr : ids.data());
    extended.xyz.resize(points.size() * static_cast<std::size_t>(dims));
    copy_points(points, extended);
    std::vector<point_id> original(points.size());
    std::iota(original.begin(), original.end(), 0);
    detail::append_images(points, options.search, extended, original, 0);
    for (std::size_t k = 0; k < original.size(); ++k) {
      const auto i = static_cast<std::size_t>(original[k]);
      const std::int64_t id = ids.empty() ? static_cast<std::int64_t>(i) : ids[i];
      extended_ids.push_back(k < points.size() ? id : -(id + 1));
      if (rule) extended_radii.push_back(radii[i]);
    }
    points = extended.view();
    if (rule) radii = extended_radii;
  }
  const std::vector<std::int64_t>& point_ids = extended_ids.empty() ? ids : extended_ids;
  const auto radius = [&](std::size_t i) { return rule ? radii[i] : 0.0; };
  detail::Traffic traffic;
  std::array<double, 5> seconds{};  // preprocess, decompose, communicate, search, gather
  Stopwatch clock;

  // Preprocess: the global bounding box; a horizon widened by the rounding of the box tests.
  const Bounds box = global_bounds(rank, points);
  const double reach = halo_reach(box, dims, options.search.horizon);
  seconds[0] = clock.lap();

  std::vector<Packed> owned, ghosts;
  if (global_count > 0) {
    if (options.exchange == Exchange::thesis) {
      for (std::size_t i = 0; i < points.size(); ++i) owned.push_back(pack(points, i, point_ids[i], radius(i)));
      seconds[1] = clock.lap();
      ghosts = thesis_ghosts(rank, owned, box, dims, global_count, options.search.horizon, width, first_query,
                             traffic);
      seconds[2] = clock.lap();
    } else {
      const Decomposition d = decompose(rank, points, global_count, box, options.decomposition, everyone_has_all);
      if (everyone_has_all) {
        // Overlap: keep what lies in or near the sub-domain, straight from the input.
        for (std::size_t i = 0; i < points.size(); ++i) {
          const Packed p = pack(points, i, point_ids.empty() ? static_cast<std::int64_t>(i) : point_ids[i], radius(i));
          if (d.owner(p.data()) == rank.id) owned.push_back(p);
          else if (is_reference(p, first_query) && d.box(rank.id).near(p.data(), dims, reach)) ghosts.push_back(p);
        }
        seconds[1] = clock.lap();
      } else {
        std::vector<std::vector<Packed>> outgoing(static_cast<std::size_t>(rank.size));
        for (std::size_t i = 0; i < points.size(); ++i) {
          const Packed p = pack(points, i, point_ids[i], radius(i));
          outgoing[static_cast<std::size_t>(d.owner(p.data()))].push_back(p);
        }
        owned = detail::exchange_all(comm, outgoing, width, traffic);  // migration to owners
        seconds[1] = clock.lap();
        ghosts = halo_ghosts(rank, owned, d, dims, reach, width, first_query, traffic);
        seconds[2] = clock.lap();
      }
    }
  }
  OwnedRows out = search_owned(owned, ghosts, dims, options.search, rule, first_query);
  seconds[3] = clock.lap();

  if (stats) {
    std::array<double, 5> worst{};
    MPI_Allreduce(seconds.data(), worst.data(), 5, MPI_DOUBLE, MPI_MAX, comm);
    const std::array<std::int64_t, 3> mine{traffic.bytes, traffic.messages, static_cast<std::int64_t>(ghosts.size())};
    std::array<std::int64_t, 3> sum{}, most{};
    MPI_Allreduce(mine.data(), sum.data(), 3, MPI_INT64_T, MPI_SUM, comm);
    MPI_Allreduce(mine.data(), most.data(), 3, MPI_INT64_T, MPI_MAX, comm);
    const std::int64_t n_owned = static_cast<std::int64_t>(owned.size());
    std::int64_t fewest = 0, largest = 0;
    MPI_Allreduce(&n_owned, &fewest, 1, MPI_INT64_T, MPI_MIN, comm);
    MPI_Allreduce(&n_owned, &largest, 1, MPI_INT64_T, MPI_MAX, comm);
    *stats = DistributedStats{worst[0], worst[1], worst[2], worst[3], 0, sum[0], sum[1], most[0], most[1],
                              sum[2], fewest, largest, rank.size};
  }
  return out;
}

}  // namespace

OwnedRows search_distributed(MPI_Comm comm, PointView points, const std::vector<std::int64_t>& ids,
                             std::size_t global_count, const DistributedOptions& options,
                             DistributedStats* stats) {
  if (detail::needs_cell_search(options.search))
    return detail::search_distributed_cell(comm, points, ids, {}, std::nullopt, global_count, options, stats);
  return distributed_rows(comm, points, ids, {}, std::nullopt, global_count, options, stats);
}

OwnedRows search_distributed(MPI_Comm comm, PointView points, const std::vector<std::int64_t>& ids,
                             std::span<const double> radii, RadiusRule rule, std::size_t global_count,
                             const DistributedOptions& options, DistributedStats* stats) {
  if (detail::needs_cell_search(options.search))
    return detail::search_distributed_cell(comm, points, ids, radii, rule, global_count, options, stats);
  DistributedOptions reach = options;  // the ghosts reach the largest radius of all
  reach.search.horizon = largest_radius(comm, points, ids, radii, rule, options.search);
  return distributed_rows(comm, points, ids, radii, rule, global_count, reach, stats);
}

OwnedRows search_distributed_queries(MPI_Comm comm, PointView queries, const std::vector<std::int64_t>& query_ids,
                                     std::size_t global_queries, PointView references,
                                     const std::vector<std::int64_t>& reference_ids, std::size_t global_references,
                                     const DistributedOptions& options, std::span<const double> radii,
                                     DistributedStats* stats) {
  if (options.search.half) throw Error("half lists are about one point set, not queries against references");
  if (detail::needs_cell_search(options.search))
    throw Error("cell: queries cannot be combined with a cell, outputs or self_interaction");
  if (queries.dims() != references.dims())
    throw Error("queries are " + std::to_string(queries.dims()) + "-D but the references " +
                std::to_string(references.dims()) + "-D");
  const bool everyone_has_all = options.exchange == Exchange::overlap;
  if (!everyone_has_all && (query_ids.size() != queries.size() || reference_ids.size() != references.size()))
    throw Error("search_distributed_queries: a global id for every point held");
  DistributedOptions reach = options;
  if (!radii.empty())
    reach.search.horizon = largest_radius(comm, queries, query_ids, radii, RadiusRule::gather, options.search, "query");
  // One point set: the references, then the queries with ids from global_references on.
  const int dims = queries.dims();
  PointSet both{dims, std::vector<double>((references.size() + queries.size()) * static_cast<std::size_t>(dims))};
  std::vector<std::int64_t> ids;
  std::vector<double> both_radii;
  const auto first_query = static_cast<std::int64_t>(global_references);
  for (std::size_t i = 0; i < references.size(); ++i) {
    for (int a = 0; a < dims; ++a) both.xyz[i * dims + a] = references(i, a);
    ids.push_back(everyone_has_all ? static_cast<std::int64_t>(i) : reference_ids[i]);
    if (!radii.empty()) both_radii.push_back(0);  // unused: a row is tested with its query's radius
  }
  for (std::size_t q = 0; q < queries.size(); ++q) {
    for (int a = 0; a < dims; ++a) both.xyz[(references.size() + q) * dims + a] = queries(q, a);
    ids.push_back(first_query + (everyone_has_all ? static_cast<std::int64_t>(q) : query_ids[q]));
    if (!radii.empty()) both_radii.push_back(radii[q]);
  }
  const std::optional<RadiusRule> rule = radii.empty() ? std::nullopt : std::optional{RadiusRule::gather};
  return distributed_rows(comm, both.view(), ids, both_radii, rule, global_references + global_queries, reach,
                          stats, first_query);
}

bool gather_fits(MPI_Comm comm, std::int64_t entries, const SearchOptions& options, int root) {
  int rank = 0, fits = 1;
  MPI_Comm_rank(comm, &rank);
  if (rank == root) try {
      detail::check_list_fits(2 * entries, options);  // the list, and the rows received for it
    } catch (const ListTooLarge&) {
      fits = 0;
    }
  MPI_Bcast(&fits, 1, MPI_INT, root, comm);
  return fits != 0;
}

NeighborList gather_rows(MPI_Comm comm, const OwnedRows& owned, std::size_t global_count, bool half, int root) {
  int id = 0, size = 1;
  MPI_Comm_rank(comm, &id);
  MPI_Comm_size(comm, &size);
  constexpr std::size_t chunk = std::size_t{1} << 28;  // items per message
  const std::int64_t header[2] = {static_cast<std::int64_t>(owned.ids.size()), owned.rows.total()};
  std::vector<std::int64_t> headers(static_cast<std::size_t>(2 * size));
  MPI_Gather(header, 2, MPI_INT64_T, headers.data(), 2, MPI_INT64_T, root, comm);
  // The per-entry geometry of a cell search travels beside the ids (every rank asked for the same).
  const PairOutputs outputs = owned.rows.outputs();
  const auto dims = static_cast<std::size_t>(owned.rows.geometry_dims());

  auto send_all = [&](const void* data, std::size_t count, MPI_Datatype type, std::size_t item) {
    for (std::size_t at = 0; at < count; at += chunk)
      MPI_Send(static_cast<const char*>(data) + at * item, static_cast<int>(std::min(chunk, count - at)), type, root,
               0, comm);
  };
  if (id != root) {
    std::vector<std::int64_t> lengths(owned.ids.size());
    for (std::size_t r = 0; r < lengths.size(); ++r) lengths[r] = static_cast<std::int64_t>(owned.rows.row_size(r));
    send_all(owned.ids.data(), owned.ids.size(), MPI_INT64_T, 8);
    send_all(lengths.data(), lengths.size(), MPI_INT64_T, 8);
    send_all(owned.rows.indices().data(), owned.rows.indices().size(), MPI_INT32_T, 4);
    send_all(owned.rows.shifts().data(), owned.rows.shifts().size(), MPI_INT32_T, 4);
    send_all(owned.rows.distances().data(), owned.rows.distances().size(), MPI_DOUBLE, 8);
    send_all(owned.rows.vectors().data(), owned.rows.vectors().size(), MPI_DOUBLE, 8);
    return NeighborList({0}, {}, half);
  }
  auto receive_all = [&](void* data, std::size_t count, MPI_Datatype type, std::size_t item, int from) {
    for (std::size_t at = 0; at < count; at += chunk)
      MPI_Recv(static_cast<char*>(data) + at * item, static_cast<int>(std::min(chunk, count - at)), type, from, 0,
               comm, MPI_STATUS_IGNORE);
  };
  // Per rank: global ids, row lengths, entries (and their geometry).
  struct Received {
    std::vector<std::int64_t> ids, lengths;
    NeighborList rows;
  };
  std::vector<Received> ranks(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) {
    const auto n = static_cast<std::size_t>(headers[static_cast<std::size_t>(2 * r)]);
    const auto total = static_cast<std::size_t>(headers[static_cast<std::size_t>(2 * r + 1)]);
    Received& from = ranks[static_cast<std::size_t>(r)];
    if (r == root) {
      from.ids = owned.ids;
      for (std::size_t i = 0; i < n; ++i) from.lengths.push_back(static_cast<std::int64_t>(owned.rows.row_size(i)));
      continue;
    }
    from.ids.resize(n);
    from.lengths.resize(n);
    Buffer<point_id> indices(total);
    Buffer<std::int32_t> shifts(outputs.shifts ? total * dims : 0);
    Buffer<double> distances(outputs.distances ? total : 0), vectors(outputs.vectors ? total * dims : 0);
    receive_all(from.ids.data(), n, MPI_INT64_T, 8, r);
    receive_all(from.lengths.data(), n, MPI_INT64_T, 8, r);
    receive_all(indices.data(), total, MPI_INT32_T, 4, r);
    receive_all(shifts.data(), shifts.size(), MPI_INT32_T, 4, r);
    receive_all(distances.data(), distances.size(), MPI_DOUBLE, 8, r);
    receive_all(vectors.data(), vectors.size(), MPI_DOUBLE, 8, r);
    from.rows = NeighborList({0}, std::move(indices), half);
    from.rows.set_geometry(outputs, std::move(shifts), std::move(distances), std::move(vectors),
                           static_cast<int>(dims));
  }
  Buffer<std::int64_t> offsets(global_count + 1, 0);
  for (const Received& from : ranks)
    for (std::size_t i = 0; i < from.ids.size(); ++i)
      offsets[static_cast<std::size_t>(from.ids[i]) + 1] = from.lengths[i];
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  const auto total = static_cast<std::size_t>(offsets.back());
  Buffer<point_id> indices(total);
  Buffer<std::int32_t> shifts(outputs.shifts ? total * dims : 0);
  Buffer<double> distances(outputs.distances ? total : 0), vectors(outputs.vectors ? total * dims : 0);
  for (int r = 0; r < size; ++r) {
    const Received& from = ranks[static_cast<std::size_t>(r)];
    const NeighborList& rows = r == root ? owned.rows : from.rows;
    std::size_t at = 0;  // the rank's entry
    for (std::size_t i = 0; i < from.ids.size(); ++i) {
      const auto to = static_cast<std::size_t>(offsets[static_cast<std::size_t>(from.ids[i])]);
      const auto length = static_cast<std::size_t>(from.lengths[i]);
      std::copy_n(rows.indices().data() + at, length, indices.data() + to);
      if (outputs.shifts) std::copy_n(rows.shifts().data() + at * dims, length * dims, shifts.data() + to * dims);
      if (outputs.distances) std::copy_n(rows.distances().data() + at, length, distances.data() + to);
      if (outputs.vectors) std::copy_n(rows.vectors().data() + at * dims, length * dims, vectors.data() + to * dims);
      at += length;
    }
  }
  NeighborList list(std::move(offsets), std::move(indices), half);
  list.set_geometry(outputs, std::move(shifts), std::move(distances), std::move(vectors), static_cast<int>(dims));
  return list;
}

}  // namespace horizon
