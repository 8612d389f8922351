#include "partitioned_search.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <exception>
#include <span>
#include <thread>
#include <utility>

#include "cell_search.hpp"
#include "device_part.hpp"
#include "horizon/cuda.hpp"
#include "horizon/error.hpp"
#include "horizon/grid.hpp"
#include "horizon/parts.hpp"
#include "memory_check.hpp"
#include "parallel_copy.hpp"
#include "parallel_scan.hpp"
#include "part_lists.hpp"
#include "reference_search.hpp"

namespace horizon::detail {
namespace {

/// One part. Its owned points and its halo (each ascending); on the host path, its local
/// list (owned points first, then the halo) and `global`, the global id of each local point. A
/// GPU part's local points are its own and its halo in one ascending order (`global`), the
/// owned ones at `owned_rows`; its rows stay on its GPU, their offsets also on the host.
struct Part : PartLists {
  NeighborList list;
  PartStats stats;
  DevicePart on_device;
  Buffer<std::int64_t> offsets;
};

/// How many entries row i of a local list keeps (half lists: j > i by global id).
std::int64_t kept(const NeighborList& list, std::size_t i, std::span<const point_id> global, bool half) {
  const auto row = list.row(i);
  if (!half) return static_cast<std::int64_t>(row.size());
  return std::count_if(row.begin(), row.end(), [&](point_id j) { return global[j] > global[i]; });
}

/// Writes row i of a local list at `out` in global ids: two runs ascending in global id (the
/// owned points', then the references'), which one merge sorts.
void write_row(const NeighborList& list, std::size_t i, std::span<const point_id> global, std::size_t owned,
               bool half, bool sort_rows, point_id* out) {
  point_id* references_from = nullptr;
  point_id* at = out;
  for (point_id j : list.row(i)) {
    const point_id g = global[static_cast<std::size_t>(j)];
    if (half && g <= global[i]) continue;
    if (static_cast<std::size_t>(j) >= owned && !references_from) references_from = at;
    *at++ = g;
  }
  if (sort_rows && references_from) std::inplace_merge(out, references_from, at);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Every part's lists (part_lists.hpp) moved into `parts`, with their point counts.
void take_lists(std::vector<PartLists>&& lists, std::vector<Part>& parts) {
  for (std::size_t p = 0; p < lists.size(); ++p) {
    Part& part = parts[p];
    part.stats.owned = lists[p].owned.size();
    part.stats.halo = lists[p].halo_count;
    static_cast<PartLists&>(part) = std::move(lists[p]);
  }
}

/// Runs work(p) for every part on a thread of its own, its OpenMP regions on a share of the
/// caller's threads (a thread of its own starts teams of its own: p teams of every core crowded
/// the cores); the first failure is rethrown once all have ended.
template <class Work>
void on_each_part(int count, Work&& work) {
  std::vector<std::exception_ptr> failures(static_cast<std::size_t>(count));
  std::vector<std::thread> threads;
  const int share = std::max(1, omp_get_max_threads() / count);
  for (int p = 0; p < count; ++p)
    threads.emplace_back([&, p] {
      omp_set_num_threads(share);
      try {
        work(p);
      } catch (...) {
        failures[static_cast<std::size_t>(p)] = std::current_exception();
      }
    });
  for (auto& t : threads) t.join();
  for (const auto& failure : failures)
    if (failure) std::rethrow_exception(failure);
}

/// The checks of a search cut into parts: points, horizon, open boundaries.
void check_parts_input(PointView points, const SearchOptions& options) {
  validate(points);
  validate_horizon(options.horizon, options.cells_per_horizon);
  if (is_periodic(options) || needs_cell_search(options))
    throw Error("a search in parts is for open boundaries: no periodic box, cell or pair outputs");
}

/// The coordinates of points global[0], global[1], ... (in `xyz`), as a view.
PointView gather(PointView points, std::span<const point_id> global, ScratchBuffer<double>& xyz) {
  const int dims = points.dims();
  xyz.resize(global.size() * static_cast<std::size_t>(dims));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(global.size()); ++i)
    for (int a = 0; a < dims; ++a) xyz[static_cast<std::size_t>(i) * dims + a] = points(static_cast<std::size_t>(global[i]), a);
  return PointView(xyz.data(), global.size(), dims);
}

/// Searches a part on its GPU, its rows left there (part.global and part.owned_rows set).
void search_part_on_device(PointView points, Part& part, const SearchOptions& part_options) {
  const auto start = std::chrono::steady_clock::now();
  SearchOptions options = part_options;
  options.devices.clear();
  ScratchBuffer<double> xyz;
  SearchStats stats;
  part.on_device = search_local_part({gather(points, part.global, xyz), part.global, part.owned_rows}, options, &stats);
  part.stats.device = part_options.device;
  part.stats.build_seconds = stats.kernel_seconds;
  part.stats.seconds = seconds_since(start);
}

/// Searches a part: owned points first, then its halo, as references only.
void search_part(PointView points, Part& part, const SearchOptions& part_options) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t owned = part.owned.size();
  ScratchBuffer<point_id>& global = part.global;
  global.resize(owned + part.halo.size());
  std::copy(part.owned.begin(), part.owned.end(), global.begin());
  std::copy(part.halo.begin(), part.halo.end(), global.begin() + static_cast<std::ptrdiff_t>(owned));
  ScratchBuffer<double> xyz;
  const PointView local = gather(points, global, xyz);

  part.list = NeighborList({0}, {}, false);
  if (owned > 0) {
    SearchOptions o = part_options;
    o.half = false;
    o.queries = owned;
    o.devices.clear();
    SearchStats stats;
    part.list = search(local, o, &stats);
    part.stats.build_seconds =
        stats.backend == Backend::cuda ? stats.kernel_seconds : stats.grid_seconds + stats.search_seconds;
  }
  part.stats.device = part_options.device;
  part.stats.seconds = seconds_since(start);
}

}  // namespace

void place_rows(const PartRows& part, std::size_t first, std::size_t last, const point_id* staged,
                const std::int64_t* at, point_id* indices) {
  // Rows whose places follow one another (a part's points are often runs of consecutive ids)
  // go as one copy, streamed past the caches when long: like the one-GPU path's copy, the
  // destination is then not read before it is written.
  constexpr std::int64_t block = 1024;
  constexpr std::size_t stream_from = std::size_t{4} << 10;
  const std::int64_t* offsets = part.offsets.data();
  const auto blocks = (static_cast<std::int64_t>(last - first) + block - 1) / block;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::size_t end = std::min(last, first + static_cast<std::size_t>((b + 1) * block));
    for (std::size_t r = first + static_cast<std::size_t>(b * block); r < end;) {
      const std::int64_t place = at[part.ids[r]];
      std::size_t run_end = r + 1;
      while (run_end < end && at[part.ids[run_end]] == place + (offsets[run_end] - offsets[r])) ++run_end;
      const auto bytes = static_cast<std::size_t>(offsets[run_end] - offsets[r]) * sizeof(point_id);
      const point_id* from = staged + (offsets[r] - offsets[first]);
      if (bytes >= stream_from)
        stream_copy(indices + place, from, bytes);
      else
        std::memcpy(indices + place, from, bytes);
      r = run_end;
    }
  }
}

NeighborList rows_in_global_ids(const NeighborList& list, std::span<const point_id> global, std::size_t owned,
                                bool half, bool sort_rows, std::size_t references_from) {
  if (references_from == SIZE_MAX) references_from = owned;
  Buffer<std::int64_t> offsets(owned + 1);
  offsets[0] = 0;
  const auto rows = static_cast<std::int64_t>(owned);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < rows; ++i) offsets[i + 1] = kept(list, static_cast<std::size_t>(i), global, half);
  inclusive_scan(offsets.data() + 1, owned, omp_get_max_threads());
  Buffer<point_id> indices(static_cast<std::size_t>(offsets[owned]));
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::int64_t i = 0; i < rows; ++i)
    write_row(list, static_cast<std::size_t>(i), global, references_from, half, sort_rows, indices.data() + offsets[i]);
  return NeighborList(std::move(offsets), std::move(indices), half);
}

NeighborList search_parts(PointView points, const SearchOptions& options,
                          const std::vector<SearchOptions>& part_options, SearchStats& stats) {
  auto clock = std::chrono::steady_clock::now();
  const int count = static_cast<int>(part_options.size());
  const PartCut cut(points, count, options.horizon);
  const std::size_t n = points.size();
  std::vector<Part> parts(static_cast<std::size_t>(count));
  // GPU parts keep their rows on their GPUs until each row is copied to its place; a part that
  // does not fit there sends every part down the host path (in batches) and the assembly below.
  bool on_devices = options.queries == 0 &&
                    std::all_of(part_options.begin(), part_options.end(),
                                [](const SearchOptions& o) { return o.backend == Backend::cuda; });
  take_lists(cut.lists(points, on_devices), parts);
  stats.partition_seconds = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  if (on_devices) {
    try {
      on_each_part(count, [&](int p) {
        search_part_on_device(points, parts[p], part_options[p]);
        parts[p].offsets = host_offsets(parts[p].on_device);
      });
    } catch (const DeviceOutOfMemory&) {
      on_devices = false;
      for (Part& part : parts) part = Part();
      take_lists(cut.lists(points, false), parts);
    }
  }
  if (!on_devices) on_each_part(count, [&](int p) { search_part(points, parts[p], part_options[p]); });
  const double parts_seconds = seconds_since(clock);

  // Rows in input order, each written once, in global ids, straight from its part's rows.
  clock = std::chrono::steady_clock::now();
  Buffer<std::int64_t> offsets(n + 1);
  offsets[0] = 0;
  for (Part& part : parts) {
    std::int64_t entries = 0;
    const auto rows = static_cast<std::int64_t>(part.owned.size());
#pragma omp parallel for schedule(static) reduction(+ : entries)
    for (std::int64_t r = 0; r < rows; ++r) {
      const std::int64_t size = on_devices ? part.offsets[r + 1] - part.offsets[r]
                                           : kept(part.list, static_cast<std::size_t>(r), part.global, options.half);
      offsets[static_cast<std::size_t>(part.owned[r]) + 1] = size;
      entries += size;
    }
    part.stats.entries = entries;
  }
  inclusive_scan(offsets.data() + 1, n, omp_get_max_threads());
  check_list_fits(offsets[n], options);
  Buffer<point_id> indices(static_cast<std::size_t>(offsets[n]));
  if (on_devices) {
    // Faulted in first, on all cores: the rows then arrive at copy speed.
    parallel_touch(indices.data(), indices.size() * sizeof(point_id));
    std::vector<PartRows> rows;
    for (const Part& part : parts) rows.push_back({&part.on_device, part.offsets, part.owned});
    copy_part_rows(rows, offsets.data(), indices.data());
  } else {
    for (Part& part : parts) {
      const auto rows = static_cast<std::int64_t>(part.owned.size());
#pragma omp parallel for schedule(dynamic, 1024)
      for (std::int64_t r = 0; r < rows; ++r) {
        const std::size_t g = static_cast<std::size_t>(part.owned[r]);
        write_row(part.list, static_cast<std::size_t>(r), part.global, part.owned.size(), options.half,
                  options.sort_rows, indices.data() + offsets[g]);
      }
      part.list = NeighborList();  // freed as soon as its rows are placed
    }
  }
  for (Part& part : parts) stats.parts.push_back(part.stats);
  stats.assemble_seconds = seconds_since(clock);
  stats.search_seconds = stats.partition_seconds + parts_seconds + stats.assemble_seconds;
  stats.threads = count;
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

}  // namespace horizon::detail

namespace horizon {

std::vector<PointPart> cut_into_parts(PointView points, int parts, const SearchOptions& options) {
  detail::check_parts_input(points, options);
  std::vector<detail::PartLists> lists = detail::PartCut(points, parts, options.horizon).lists(points, false);
  std::vector<PointPart> result(static_cast<std::size_t>(parts));
  for (int p = 0; p < parts; ++p) {
    result[p].owned.assign(lists[p].owned.begin(), lists[p].owned.end());
    result[p].halo.assign(lists[p].halo.begin(), lists[p].halo.end());
  }
  return result;
}

std::vector<OwnedPart> search_in_parts(PointView points, int parts, const SearchOptions& options) {
  detail::check_parts_input(points, options);
  std::vector<detail::Part> lists(static_cast<std::size_t>(parts));
  detail::take_lists(detail::PartCut(points, parts, options.horizon).lists(points, false), lists);
  std::vector<OwnedPart> result(static_cast<std::size_t>(parts));
  for (int p = 0; p < parts; ++p) {
    detail::Part& part = lists[p];
    detail::search_part(points, part, options);
    result[p].rows = detail::rows_in_global_ids(part.list, part.global, part.owned.size(), options.half, options.sort_rows);
    result[p].ids.assign(part.owned.begin(), part.owned.end());
    result[p].halo = part.halo.size();
  }
  return result;
}

std::vector<DevicePart> search_device_parts(PointView points, const SearchOptions& options, SearchStats* stats) {
  detail::check_parts_input(points, options);
  const std::vector<int> devices = options.devices.empty() ? std::vector<int>{options.device} : options.devices;
  const int count = static_cast<int>(devices.size());
  auto clock = std::chrono::steady_clock::now();
  std::vector<detail::Part> parts(static_cast<std::size_t>(count));
  detail::take_lists(detail::PartCut(points, count, options.horizon).lists(points, true), parts);
  const double partition_seconds = detail::seconds_since(clock);
  clock = std::chrono::steady_clock::now();
  detail::on_each_part(count, [&](int p) {
    SearchOptions one = options;
    one.backend = Backend::cuda;
    one.device = devices[static_cast<std::size_t>(p)];
    detail::search_part_on_device(points, parts[p], one);
    parts[p].on_device.ids.assign(parts[p].owned.begin(), parts[p].owned.end());
    parts[p].stats.entries = parts[p].on_device.rows.total();
  });
  std::vector<DevicePart> result;
  if (stats) {
    *stats = SearchStats{};
    stats->backend = Backend::cuda;
    stats->threads = count;
    stats->partition_seconds = partition_seconds;
    stats->search_seconds = partition_seconds + detail::seconds_since(clock);
  }
  for (detail::Part& part : parts) {
    if (stats) stats->parts.push_back(part.stats);
    result.push_back(std::move(part.on_device));
  }
  return result;
}

DevicePart search_device_part(PointView points, const PointPart& part, const SearchOptions& options,
                              SearchStats* stats) {
  detail::check_parts_input(points, options);
  // The local points: the owned ones and the halo merged into one ascending order.
  const std::size_t n = points.size();
  std::vector<point_id> global(part.owned.size() + part.halo.size());
  std::merge(part.owned.begin(), part.owned.end(), part.halo.begin(), part.halo.end(), global.begin());
  for (std::size_t r = 0; r < global.size(); ++r)
    if (global[r] < 0 || static_cast<std::size_t>(global[r]) >= n || (r > 0 && global[r] <= global[r - 1]))
      throw Error("part: its owned and halo ids must ascend, be distinct and lie in 0.." + std::to_string(n - 1) +
                  " (id " + std::to_string(global[r]) + ")");
  std::vector<point_id> owned_rows;
  owned_rows.reserve(part.owned.size());
  for (std::size_t r = 0, k = 0; r < global.size(); ++r)
    if (k < part.owned.size() && global[r] == part.owned[k]) {
      owned_rows.push_back(static_cast<point_id>(r));
      ++k;
    }
  ScratchBuffer<double> xyz;
  SearchStats local;
  DevicePart result = detail::search_local_part({detail::gather(points, global, xyz), global, owned_rows}, options,
                                                stats ? stats : &local);
  result.ids = part.owned;
  return result;
}

}  // namespace horizon
