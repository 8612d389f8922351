#include "distributed_cell_search.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "../core/cell_images.hpp"
#include "../core/cell_problem.hpp"
#include "../core/parallel_scan.hpp"
#include "agree.hpp"
#include "exchange.hpp"
#include "horizon/error.hpp"
#include "horizon/stopwatch.hpp"

namespace horizon::detail {
namespace {

struct Ranks {
  MPI_Comm comm;
  int id = 0, size = 1;
};

/// The first key of each rank's range and the end of the last: rank r holds [at[r], at[r + 1]).
struct Ranges {
  std::vector<std::int64_t> at;
  int owner(std::int64_t key) const {
    return static_cast<int>(std::upper_bound(at.begin(), at.end(), key) - at.begin()) - 1;
  }
};

/// Blocks of n ids: rank r's is [n r / P, n (r + 1) / P).
Ranges blocks_of(std::size_t n, int size) {
  Ranges blocks;
  for (int r = 0; r <= size; ++r)
    blocks.at.push_back(static_cast<std::int64_t>(n * static_cast<std::size_t>(r) / static_cast<std::size_t>(size)));
  return blocks;
}

/// The caller's points (and radii) of this rank's block of ids, in id order.
struct Block {
  std::int64_t first = 0;
  PointSet points;
  std::vector<double> radii;
};

/// Every held point to the rank that owns its id's block. Error on every rank when an id is out
/// of [0, n), held twice or by no rank.
Block directory(const Ranks& ranks, PointView points, const std::vector<std::int64_t>& ids,
                std::span<const double> radii, bool with_radii, const Ranges& blocks, bool everyone_has_all,
                Traffic& traffic) {
  const int dims = points.dims();
  Block block;
  block.first = blocks.at[static_cast<std::size_t>(ranks.id)];
  const auto count = static_cast<std::size_t>(blocks.at[static_cast<std::size_t>(ranks.id) + 1] - block.first);
  block.points = PointSet{dims, std::vector<double>(count * static_cast<std::size_t>(dims))};
  if (with_radii) block.radii.resize(count);
  if (everyone_has_all) {  // overlap: every rank passed all points
    for (std::size_t k = 0; k < count; ++k) {
      const auto i = static_cast<std::size_t>(block.first) + k;
      for (int a = 0; a < dims; ++a) block.points.xyz[k * dims + a] = points(i, a);
      if (with_radii) block.radii[k] = radii[i];
    }
    return block;
  }
  const auto n = static_cast<std::int64_t>(blocks.at.back());
  std::string failure;
  std::vector<std::vector<Packed>> outgoing(static_cast<std::size_t>(ranks.size));
  for (std::size_t i = 0; i < points.size() && failure.empty(); ++i) {
    if (ids[i] < 0 || ids[i] >= n) {
      failure = "search_distributed: held point " + std::to_string(i) + " has global id " + std::to_string(ids[i]) +
                ", not in [0, " + std::to_string(n) + ")";
      break;
    }
    outgoing[static_cast<std::size_t>(blocks.owner(ids[i]))].push_back(
        pack(points, i, ids[i], with_radii ? radii[i] : 0.0));
  }
  agree(ranks.comm, failure);
  const std::vector<Packed> received = exchange_all(ranks.comm, outgoing, with_radii ? 5 : 4, traffic);
  std::vector<char> seen(count, 0);
  for (const Packed& p : received) {
    const auto k = static_cast<std::size_t>(static_cast<std::int64_t>(p[3]) - block.first);
    if (seen[k]) failure = "search_distributed: global id " + std::to_string(static_cast<std::int64_t>(p[3])) +
                           " is held more than once";
    seen[k] = 1;
    for (int a = 0; a < dims; ++a) block.points.xyz[k * dims + a] = p[static_cast<std::size_t>(a)];
    if (with_radii) block.radii[k] = p[4];
  }
  const auto missing = std::find(seen.begin(), seen.end(), 0);
  if (failure.empty() && missing != seen.end())
    failure = "search_distributed: no rank holds global id " + std::to_string(block.first + (missing - seen.begin())) +
              " (the ids must be 0 to " + std::to_string(n - 1) + ", each held once)";
  agree(ranks.comm, failure);
  return block;
}

/// For each of `keys` (ascending), the W doubles its owner (ranges.owner, non-decreasing in the
/// key) answers with `answer(key)`: the keys go to their owners, the answers come back.
template <std::size_t W, class Answer>
std::vector<std::array<double, W>> fetch(const Ranks& ranks, const std::vector<std::int64_t>& keys,
                                         const Ranges& ranges, Answer&& answer, Traffic& traffic) {
  const auto size = static_cast<std::size_t>(ranks.size);
  std::vector<int> send_counts(size, 0), receive_counts(size), send_at(size), receive_at(size);
  for (const std::int64_t key : keys) ++send_counts[static_cast<std::size_t>(ranges.owner(key))];
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, ranks.comm);
  std::exclusive_scan(send_counts.begin(), send_counts.end(), send_at.begin(), 0);
  std::exclusive_scan(receive_counts.begin(), receive_counts.end(), receive_at.begin(), 0);
  std::vector<std::int64_t> asked(static_cast<std::size_t>(receive_at.back() + receive_counts.back()));
  MPI_Alltoallv(keys.data(), send_counts.data(), send_at.data(), MPI_INT64_T, asked.data(), receive_counts.data(),
                receive_at.data(), MPI_INT64_T, ranks.comm);
  std::vector<std::array<double, W>> answers(asked.size()), back(keys.size());
  for (std::size_t k = 0; k < asked.size(); ++k) answers[k] = answer(asked[k]);
  MPI_Datatype record;
  MPI_Type_contiguous(static_cast<int>(W), MPI_DOUBLE, &record);
  MPI_Type_commit(&record);
  MPI_Alltoallv(answers.data(), receive_counts.data(), receive_at.data(), record, back.data(), send_counts.data(),
                send_at.data(), record, ranks.comm);
  MPI_Type_free(&record);
  for (std::size_t r = 0; r < size; ++r) {
    if (static_cast<int>(r) == ranks.id) continue;
    traffic.bytes += 8 * (send_counts[r] + static_cast<std::int64_t>(W) * receive_counts[r]);
    traffic.messages += (send_counts[r] > 0) + (receive_counts[r] > 0);
  }
  return back;
}

/// The distinct ids (below a bound) a list's entries name, each found again by its place among
/// them: a bit per id and the bits counted per word.
class DistinctIds {
public:
  explicit DistinctIds(std::int64_t bound) : bits_(static_cast<std::size_t>(bound / 64 + 1), 0) {}
  void add(std::int64_t id) { bits_[static_cast<std::size_t>(id >> 6)] |= std::uint64_t{1} << (id & 63); }
  /// After the last add: the ids, ascending.
  std::vector<std::int64_t> ids() {
    before_.resize(bits_.size());
    std::vector<std::int64_t> ids;
    for (std::size_t w = 0; w < bits_.size(); ++w) {
      before_[w] = static_cast<std::int64_t>(ids.size());
      for (std::uint64_t word = bits_[w]; word != 0; word &= word - 1)
        ids.push_back(static_cast<std::int64_t>(w * 64) + std::countr_zero(word));
    }
    return ids;
  }
  std::size_t place(std::int64_t id) const {
    const auto w = static_cast<std::size_t>(id >> 6);
    return static_cast<std::size_t>(before_[w] + std::popcount(bits_[w] & ((std::uint64_t{1} << (id & 63)) - 1)));
  }

private:
  std::vector<std::uint64_t> bits_;
  std::vector<std::int64_t> before_;
};

/// The points of `xyz` ordered by the cells of side `side` they lie in (z slowest), as indices.
std::vector<std::uint32_t> spatial_order(std::span<const double> xyz, int dims, double side) {
  const std::size_t n = xyz.size() / static_cast<std::size_t>(dims);
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int a = 0; a < dims; ++a) {
    lo[a] = std::numeric_limits<double>::infinity();
    hi[a] = -lo[a];
    for (std::size_t k = 0; k < n; ++k) {
      lo[a] = std::min(lo[a], xyz[k * dims + a]);
      hi[a] = std::max(hi[a], xyz[k * dims + a]);
    }
  }
  std::uint64_t cells[3] = {1, 1, 1};
  for (int a = 0; a < dims; ++a)  // at most 2^20 cells a side: the keys fit in 64 bits
    cells[a] = n == 0 ? 1 : static_cast<std::uint64_t>(std::min((hi[a] - lo[a]) / side, 1048575.0)) + 1;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t key = 0;
    for (int a = dims - 1; a >= 0; --a) {
      const auto c = static_cast<std::uint64_t>((xyz[k * dims + a] - lo[a]) / (hi[a] - lo[a] + side) * cells[a]);
      key = key * cells[a] + std::min(c, cells[a] - 1);
    }
    keyed[k] = {key, static_cast<std::uint32_t>(k)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = keyed[k].second;
  return order;
}

std::int64_t all_sum(MPI_Comm comm, std::int64_t mine) {
  std::int64_t sum = 0;
  MPI_Allreduce(&mine, &sum, 1, MPI_INT64_T, MPI_SUM, comm);
  return sum;
}

double all_max(MPI_Comm comm, double mine) {
  double most = 0;
  MPI_Allreduce(&mine, &most, 1, MPI_DOUBLE, MPI_MAX, comm);
  return most;
}

// What a row's point (query) and a candidate (reference) bring to its measurement.
using QueryRecord = std::array<double, 7>;      // x, y, z, radius, wraps w (3)
using ReferenceRecord = std::array<double, 8>;  // x_j, y_j, z_j, j, radius_j, S_ref (3): S = S_ref + w_i

}  // namespace

OwnedRows search_distributed_cell(MPI_Comm comm, PointView points, const std::vector<std::int64_t>& ids,
                                  std::span<const double> radii, const std::optional<RadiusRule>& rule,
                                  std::size_t global_count, const DistributedOptions& options,
                                  DistributedStats* stats) {
  Ranks ranks{comm};
  MPI_Comm_rank(comm, &ranks.id);
  MPI_Comm_size(comm, &ranks.size);
  validate(points);
  const bool everyone_has_all = options.exchange == Exchange::overlap;
  if (everyone_has_all && points.size() != global_count)
    throw Error("search_distributed: with overlap every rank passes all " + std::to_string(global_count) +
                " points, not " + std::to_string(points.size()));
  if (!everyone_has_all && ids.size() != points.size())
    throw Error("search_distributed: " + std::to_string(points.size()) + " points but " + std::to_string(ids.size()) +
                " global ids");
  if (rule && radii.size() != points.size())
    throw Error("radii: " + std::to_string(radii.size()) + " radii for " + std::to_string(points.size()) + " points");
  if (rule && options.search.half && (*rule == RadiusRule::gather || *rule == RadiusRule::scatter))
    throw Error(std::string("radii: a half list needs a symmetric rule (max or min), not ") + radius_rule_name(*rule));
  const int dims = points.dims();
  Traffic traffic;
  Stopwatch clock;
  double communicate = 0, work = 0;

  const Ranges blocks = blocks_of(global_count, ranks.size);
  const Block block = directory(ranks, points, ids, radii, rule.has_value(), blocks, everyone_has_all, traffic);
  communicate += clock.lap();

  // The problem, checked as on one node (its radii here, named by global id), with the largest
  // horizon and coordinate of all ranks.
  const auto held = block.points.size();
  std::string failure;
  for (std::size_t k = 0; k < block.radii.size() && failure.empty(); ++k)
    if (!(std::isfinite(block.radii[k]) && block.radii[k] > 0))
      failure = "radii: point " + std::to_string(block.first + static_cast<std::int64_t>(k)) + " has radius " +
                std::to_string(block.radii[k]) + " (each must be finite and > 0)";
  agree(comm, failure);
  SearchOptions checked = options.search;
  if (rule) checked.horizon = 1;  // the radii decide; checked above
  CellProblem problem = cell_problem(block.points.view(), checked, {}, rule.value_or(RadiusRule::gather));
  problem.horizon = options.search.horizon;
  double largest = 0, extent = 0;
  for (const double r : block.radii) largest = std::max(largest, r);
  for (const double x : block.points.xyz) extent = std::max(extent, std::fabs(x));
  problem.largest = rule ? all_max(comm, largest) * (*rule == RadiusRule::sum ? 2 : 1) : options.search.horizon;
  if (!(problem.largest > 0)) problem.largest = 1;  // no points anywhere
  const double margin = image_margin(std::max(problem.largest, all_max(comm, extent)), problem);
  const int threads = options.search.backend == Backend::serial ? 1
                      : options.search.threads > 0              ? options.search.threads
                                                                : omp_get_max_threads();
  Images images;
  try {
    images = make_images(block.points.view(), problem, margin, threads);
  } catch (const Error& e) {
    failure = e.what();
  }
  agree(comm, failure);

  // References: the wrapped points and their images, numbered across ranks from `base`, in a
  // spatial order (the candidates of a row are then near each other in what is fetched below).
  const std::size_t local_references = images.xyz.size() / static_cast<std::size_t>(dims);
  const std::vector<std::uint32_t> order =
      spatial_order({images.xyz.data(), images.xyz.size()}, dims, problem.largest + margin);
  std::vector<double> ordered(images.xyz.size());
  for (std::size_t k = 0; k < local_references; ++k)
    std::copy_n(images.xyz.data() + std::size_t{order[k]} * dims, dims, ordered.data() + k * dims);
  std::int64_t base = 0;
  const auto mine = static_cast<std::int64_t>(local_references);
  MPI_Exscan(&mine, &base, 1, MPI_INT64_T, MPI_SUM, comm);
  if (ranks.id == 0) base = 0;  // MPI_Exscan leaves rank 0's result undefined
  const std::int64_t references = all_sum(comm, mine);
  if (references >= std::numeric_limits<point_id>::max())
    throw Error("cell: the points and their " + std::to_string(references - static_cast<std::int64_t>(global_count)) +
                " periodic images within the horizon must be fewer than 2^31 - 1 (a horizon of many cells?)");
  Ranges numbered{std::vector<std::int64_t>(static_cast<std::size_t>(ranks.size) + 1)};
  MPI_Allgather(&base, 1, MPI_INT64_T, numbered.at.data(), 1, MPI_INT64_T, comm);
  numbered.at.back() = references;
  std::vector<std::int64_t> query_ids(held), reference_ids(local_references);
  for (std::size_t k = 0; k < held; ++k) query_ids[k] = block.first + static_cast<std::int64_t>(k);
  for (std::size_t k = 0; k < local_references; ++k) reference_ids[k] = base + static_cast<std::int64_t>(k);
  const PointView wrapped(images.xyz.data(), held, dims), all(ordered.data(), local_references, dims);
  work += clock.lap();

  DistributedOptions inner = options;
  inner.search.horizon = problem.largest + margin;
  inner.search.half = false;
  inner.search.sort_rows = false;  // each row is put in (j, S) order below
  inner.search.box = {0, 0, 0};
  inner.search.cell = Cell{};
  inner.search.outputs = PairOutputs{};
  inner.search.self_interaction = false;
  inner.search.queries = 0;
  if (everyone_has_all) inner.exchange = Exchange::halo;  // each rank made its block's images only
  DistributedStats inner_stats;
  const OwnedRows candidates = search_distributed_queries(comm, wrapped, query_ids, global_count, all, reference_ids,
                                                          static_cast<std::size_t>(references), inner, {},
                                                          &inner_stats);
  clock.lap();

  // What the rows' points and the candidates are, from the ranks that made them.
  std::vector<std::int64_t> rows_by_id = candidates.ids;
  std::sort(rows_by_id.begin(), rows_by_id.end());
  const std::vector<QueryRecord> row_points = fetch<7>(
      ranks, rows_by_id, blocks,
      [&](std::int64_t id) {
        const auto k = static_cast<std::size_t>(id - block.first);
        QueryRecord r{0, 0, 0, rule ? block.radii[k] : 0.0};
        for (int a = 0; a < dims; ++a) r[static_cast<std::size_t>(a)] = block.points.xyz[k * dims + a];
        for (int a = 0; a < 3; ++a) r[static_cast<std::size_t>(4 + a)] = images.wraps[k * 3 + a];
        return r;
      },
      traffic);
  const NeighborList& rows = candidates.rows;
  DistinctIds named(references);
  for (const point_id k : rows.indices()) named.add(k);
  const std::vector<ReferenceRecord> candidate_points = fetch<8>(
      ranks, named.ids(), numbered,
      [&](std::int64_t number) {
        const std::size_t local = order[static_cast<std::size_t>(number - base)];
        const bool image = local >= held;
        const auto j = image ? static_cast<std::size_t>(images.image_of[local - held]) : local;
        ReferenceRecord r{0, 0, 0, static_cast<double>(block.first) + static_cast<double>(j),
                          rule ? block.radii[j] : 0.0};
        for (int a = 0; a < dims; ++a) r[static_cast<std::size_t>(a)] = block.points.xyz[j * dims + a];
        for (int a = 0; a < 3; ++a)
          r[static_cast<std::size_t>(5 + a)] =
              (image ? images.image_shift[(local - held) * 3 + a] : 0) - images.wraps[j * 3 + a];
        return r;
      },
      traffic);
  communicate += clock.lap();

  // Each candidate measured on the caller's coordinates, kept or dropped as the oracle does:
  // a pass that counts what each row keeps, then one that writes it in place (cheaper than
  // writing into the candidates' room and moving it together: every row drops i itself).
  const std::size_t count = rows.size();
  std::vector<std::size_t> row_point(count);
  for (std::size_t row = 0; row < count; ++row)
    row_point[row] = static_cast<std::size_t>(
        std::lower_bound(rows_by_id.begin(), rows_by_id.end(), candidates.ids[row]) - rows_by_id.begin());
  // Rows are visited in the spatial order of their wrapped points: neighbouring rows share
  // most of their candidates' records, which then stay in the cache.
  std::vector<double> wrapped_rows(count * static_cast<std::size_t>(dims));
  for (std::size_t row = 0; row < count; ++row) {
    const QueryRecord& me = row_points[row_point[row]];
    for (int a = 0; a < dims; ++a) {
      double moved = 0;
      for (int k = 0; k < dims; ++k) moved += me[static_cast<std::size_t>(4 + k)] * problem.frame.vectors[k][a];
      wrapped_rows[row * dims + a] = me[static_cast<std::size_t>(a)] - moved;
    }
  }
  const std::vector<std::uint32_t> visit = spatial_order(wrapped_rows, dims, problem.largest + margin);
  const double horizon_threshold = metric_threshold(problem.metric, problem.horizon);
  Buffer<std::int64_t> offsets(count + 1);
  offsets[0] = 0;
  OwnedRows out;
  out.ids = candidates.ids;
  with_dims_and_metric(dims, problem.metric, [&](auto d, auto m) {
    constexpr int D = decltype(d)::value;
    constexpr Metric M = decltype(m)::value;
    // The kept entries of a row, in (j, S) order.
    auto keep = [&](std::size_t row, std::vector<CellEntry>& kept) {
      const auto i = static_cast<point_id>(candidates.ids[row]);
      const QueryRecord& me = row_points[row_point[row]];
      kept.clear();
      for (const point_id k : rows.row(row)) {
        const ReferenceRecord& other = candidate_points[named.place(k)];
        CellEntry e;
        e.j = static_cast<point_id>(other[3]);
        for (int a = 0; a < 3; ++a)
          e.shift[a] = static_cast<std::int32_t>(other[static_cast<std::size_t>(5 + a)]) +
                       static_cast<std::int32_t>(me[static_cast<std::size_t>(4 + a)]);
        measure<D, M>(me.data(), other.data(), problem.frame, e);
        const double threshold = rule ? problem.threshold_of(me[3], other[4]) : horizon_threshold;
        if (e.accumulated < threshold && problem.keeps(i, e)) kept.push_back(e);
      }
      std::sort(kept.begin(), kept.end(), entry_before);
    };
    // Every row's kept entries, rows in the visiting order, to `use(row, kept)`.
    auto each_row = [&](auto&& use) {
#pragma omp parallel num_threads(threads) if (threads > 1 && count > 512)
      {
        std::vector<CellEntry> kept;
#pragma omp for schedule(dynamic, 256)
        for (std::int64_t k = 0; k < static_cast<std::int64_t>(count); ++k) {
          const std::size_t row = visit[static_cast<std::size_t>(k)];
          keep(row, kept);
          use(row, kept);
        }
      }
    };
    each_row([&](std::size_t row, const std::vector<CellEntry>& kept) {
      offsets[row + 1] = static_cast<std::int64_t>(kept.size());
    });
    inclusive_scan(offsets.data() + 1, count, threads);
    CellEntries entries(static_cast<std::size_t>(offsets[count]), dims, problem.outputs, problem.metric);
    each_row([&](std::size_t row, const std::vector<CellEntry>& kept) {
      auto at = static_cast<std::size_t>(offsets[row]);
      for (const CellEntry& e : kept) entries.write(at++, e);
    });
    out.rows = std::move(entries).list(std::move(offsets), options.search.half);
  });
  work += clock.lap();

  if (stats) {
    *stats = inner_stats;
    stats->communicate += all_max(comm, communicate);
    stats->search += all_max(comm, work);
    stats->bytes_sent += all_sum(comm, traffic.bytes);
    stats->messages_sent += all_sum(comm, traffic.messages);
  }
  return out;
}

}  // namespace horizon::detail
