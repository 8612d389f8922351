#include "family_search.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <numeric>
#include <optional>

#include "memory_check.hpp"
#include "parallel_for.hpp"
#include "parallel_scan.hpp"
#include "row_batches.hpp"

namespace horizon::detail {

namespace {

/// Runs of cells holding about equal numbers of points, 16 per thread, handed out dynamically so
/// dense regions do not serialise.
std::vector<CellRun> split_into_runs(const CellIndex& index, int threads) {
  const std::size_t cells = index.occupied_cells();
  if (threads <= 1) return {CellRun{0, cells}};
  const std::size_t wanted = static_cast<std::size_t>(threads) * 16;
  const std::size_t points_per_run = std::max<std::size_t>(1, index.point_count() / wanted);
  std::vector<CellRun> runs;
  std::size_t first = 0;
  while (first < cells) {
    std::size_t last = first;
    const std::int64_t start = index.points_of(first).begin;
    while (last < cells && static_cast<std::size_t>(index.points_of(last).end - start) < points_per_run) ++last;
    last = std::min(cells, std::max(last + 1, first + 1));
    runs.push_back(CellRun{first, last});
    first = last;
  }
  return runs;
}

/// Slabs of whole layers of cells (CellIndex::layer) holding about equal numbers of points, 8
/// per thread. An upper stencil reaches k layers up, so when every slab but the last spans at
/// least k layers, a slab's pairs land in it and the next one only: slabs of one parity can be
/// counted at once.
std::vector<CellRun> split_into_slabs(const CellIndex& index, int threads) {
  const std::size_t cells = index.occupied_cells();
  const std::int64_t k = index.grid().cells_per_horizon;
  const std::size_t points_per_slab = std::max<std::size_t>(1, index.point_count() / (static_cast<std::size_t>(threads) * 8));
  std::vector<CellRun> slabs;
  std::size_t first = 0;
  for (std::size_t c = 1; c < cells; ++c)
    if (index.layer(c) != index.layer(c - 1) && index.layer(c) - index.layer(first) >= k &&
        static_cast<std::size_t>(index.points_of(c).begin - index.points_of(first).begin) >= points_per_slab) {
      slabs.push_back(CellRun{first, c});
      first = c;
    }
  if (first < cells) slabs.push_back(CellRun{first, cells});
  return slabs;
}

}  // namespace

std::array<std::vector<CellBlock>, 4> count_pass_blocks(const CellIndex& index, int threads) {
  const std::vector<CellRun> slabs = split_into_slabs(index, threads);
  const Grid& grid = index.grid();
  const std::int64_t lines = grid.cells[1], wanted = 8 * static_cast<std::int64_t>(threads);
  const auto slab_count = static_cast<std::int64_t>(slabs.size());
  std::int64_t bands = 1;
  if (grid.dims == 3 && grid.dense && slab_count < wanted) {
    const std::int64_t even = ((2 * wanted + slab_count - 1) / slab_count + 1) / 2 * 2;  // colours alike
    bands = std::clamp<std::int64_t>(even, 1, std::max<std::int64_t>(1, lines / (2 * grid.cells_per_horizon)));
  }
  auto band_of = [&](std::size_t c) { return index.cell_coord(c)[1] * bands / lines; };
  std::array<std::vector<CellBlock>, 4> colours;
  for (std::size_t s = 0; s < slabs.size(); ++s) {
    std::vector<CellBlock> blocks(static_cast<std::size_t>(bands));
    for (std::size_t c = slabs[s].first; c < slabs[s].last;) {
      const std::int64_t band = band_of(c);
      std::size_t end = c + 1;
      while (end < slabs[s].last && index.layer(end) == index.layer(c) && band_of(end) == band) ++end;
      blocks[static_cast<std::size_t>(band)].push_back(CellRun{c, end});
      c = end;
    }
    for (std::size_t b = 0; b < blocks.size(); ++b)
      if (!blocks[b].empty()) colours[s % 2 * 2 + b % 2].push_back(std::move(blocks[b]));
  }
  return colours;
}

namespace {

/// Whether count_each_pair_once() gives the counts: one horizon, and every point holds a row
/// but the periodic images. A pair counts for both sides at once; the images' counts are never
/// read (a point's pairs across the box are met from its own side, with the other's image).
bool pairs_countable(const FamilyPass& pass) {
  const std::size_t queries = pass.options->queries;
  return !pass.row_radius && (queries == 0 || queries >= pass.index->row_count());
}

/// offsets[i + 1] = the family size of each point i with a row in `pass`, by the count pass over `runs`.
void count_each_row(const FamilyPass& pass, const std::vector<CellRun>& runs, int threads) {
  parallel_for_dynamic(static_cast<std::int64_t>(runs.size()), threads,
                       [&](std::int64_t r) { count_families(pass, runs[static_cast<std::size_t>(r)]); });
}

/// Row offsets of every point: the count pass over `runs` (or each pair once, over slabs),
/// scanned.
Buffer<std::int64_t> count_rows(FamilyPass& pass, const std::vector<CellRun>& runs, int threads) {
  const CellIndex& index = *pass.index;
  Buffer<std::int64_t> offsets(index.row_count() + 1);
  offsets[0] = 0;
  pass.offsets = offsets.data();
  if (pairs_countable(pass)) {
    ScratchBuffer<std::int64_t> counts(index.point_count() + CellIndex::padding);
    parallel_for(static_cast<std::int64_t>(counts.size()), threads, [&](std::int64_t p) { counts[p] = 0; });
    for (const std::vector<CellBlock>& colour : count_pass_blocks(index, threads))
      parallel_for_dynamic(static_cast<std::int64_t>(colour.size()), threads, [&](std::int64_t b) {
        for (const CellRun run : colour[static_cast<std::size_t>(b)]) count_each_pair_once(pass, run, counts.data());
      });
    const point_id* order = index.order().data();
    parallel_for(static_cast<std::int64_t>(index.occupied_cells()), threads, [&](std::int64_t c) {
      const auto [first, last] = index.rows_of(static_cast<std::size_t>(c));  // its points, then its images
      for (std::int64_t p = first; p < last; ++p) offsets[order[p] + 1] = counts[p];
    });
  } else {
    std::memset(offsets.data(), 0, offsets.size() * sizeof(std::int64_t));
    count_each_row(pass, runs, threads);
  }
  inclusive_scan(offsets.data(), offsets.size(), threads);
  return offsets;
}

void fill_rows(const FamilyPass& pass, const std::vector<CellRun>& runs, int threads) {
  parallel_for_dynamic(static_cast<std::int64_t>(runs.size()), threads,
                       [&](std::int64_t r) { fill_families(pass, runs[static_cast<std::size_t>(r)]); });
}

/// Below this many points, one thread fills each row into room for its whole stencil and moves
/// the rows together afterwards, with no count pass: the room is at most a few MB, and the
/// count was a fifth of the call (1,000 random points, 30 neighbours each, one core of the
/// 2-core Zen 4 VM: 82 -> 66 us; 100 points 7.9 -> 6.5 us; 3,000 points 292 -> 264 us).
constexpr std::size_t fill_into_room_below = 4096;

/// The list by one fill pass into room for every row (fill_into_room_below), or nothing when a
/// stencil holds 256 candidates or more: there the fill takes a cell's rows from its sorted
/// stencil when one of them is longer than the sorting network, which a row's room (its
/// stencil's size) would always claim.
std::optional<NeighborList> search_families_in_room(const CellIndex& index, const SearchOptions& options) {
  const std::size_t n = index.row_count();
  const std::size_t queries = options.queries ? options.queries : n;
  Buffer<std::int64_t> room(n + 1, 0);  // row i's room starts at room[i] once scanned
  std::vector<CellIndex::Range> stencil(static_cast<std::size_t>(index.max_stencil_rows()));
  const point_id* order = index.order().data();
  for (std::size_t c = 0; c < index.occupied_cells(); ++c) {
    const auto [first, last] = index.rows_of(c);
    if (first == last) continue;
    const int runs = index.stencil(c, stencil.data());
    std::int64_t candidates = 0;
    for (int r = 0; r < runs; ++r) {
      const CellIndex::Range& run = stencil[static_cast<std::size_t>(r)];
      candidates += run.end - run.begin;
    }
    if (candidates >= 256) return std::nullopt;
    for (std::int64_t p = first; p < last; ++p)
      if (static_cast<std::size_t>(order[p]) < queries) room[order[p] + 1] = candidates;
  }
  std::partial_sum(room.begin(), room.end(), room.begin());
  ScratchBuffer<point_id> rows(static_cast<std::size_t>(room[n]));
  Buffer<std::int64_t> offsets(n + 1, 0);  // the rows' lengths (pass.found), then their offsets
  FamilyPass pass{&index, &options};
  pass.offsets = room.data();
  pass.indices = rows.data();
  pass.found = offsets.data() + 1;
  fill_families(pass, CellRun{0, index.occupied_cells()});
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  check_list_fits(offsets[n], options);
  Buffer<point_id> indices(static_cast<std::size_t>(offsets[n]));
  for (std::size_t i = 0; i < n; ++i)
    if (const std::int64_t length = offsets[i + 1] - offsets[i]; length > 0)  // an empty list has no data()
      std::memcpy(indices.data() + offsets[i], rows.data() + room[i], static_cast<std::size_t>(length) * sizeof(point_id));
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

}  // namespace

NeighborList search_families(const CellIndex& index, const SearchOptions& options, int threads) {
  if (threads == 1 && index.row_count() < fill_into_room_below && index.row_count() == index.point_count())
    if (std::optional<NeighborList> list = search_families_in_room(index, options)) return std::move(*list);
  const std::vector<CellRun> runs = split_into_runs(index, threads);
  FamilyPass pass{&index, &options};
  Buffer<std::int64_t> offsets = count_rows(pass, runs, threads);
  check_list_fits(offsets.back(), options);
  Buffer<point_id> indices(static_cast<std::size_t>(offsets.back()));
  pass.indices = indices.data();
  fill_rows(pass, runs, threads);
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

NeighborList search_radius_classes(std::span<const RadiusClass> classes, const SearchOptions& options, int threads) {
  const std::size_t n = classes.front().index->row_count();
  std::vector<std::vector<CellRun>> runs;
  std::vector<FamilyPass> passes;
  for (const RadiusClass& one : classes) {
    runs.push_back(split_into_runs(*one.index, threads));
    passes.push_back(FamilyPass{one.index, &options});
    passes.back().row_radius = one.row_radius;
    passes.back().candidate_threshold = one.candidate_threshold;
  }
  Buffer<std::int64_t> offsets(n + 1);
  std::memset(offsets.data(), 0, offsets.size() * sizeof(std::int64_t));
  for (std::size_t c = 0; c < classes.size(); ++c) {
    passes[c].offsets = offsets.data();
    count_each_row(passes[c], runs[c], threads);
  }
  inclusive_scan(offsets.data(), offsets.size(), threads);
  check_list_fits(offsets.back(), options);
  Buffer<point_id> indices(static_cast<std::size_t>(offsets.back()));
  for (std::size_t c = 0; c < classes.size(); ++c) {
    passes[c].indices = indices.data();
    fill_rows(passes[c], runs[c], threads);
  }
  return NeighborList(std::move(offsets), std::move(indices), options.half);
}

void search_families_in_batches(const CellIndex& index, const SearchOptions& options, int threads,
                                std::int64_t batch_entries,
                                const std::function<void(const std::int64_t* offsets)>& begin,
                                const std::function<void(std::size_t first, std::size_t last, const point_id* ids)>& rows) {
  const std::size_t n = index.row_count();
  const std::vector<CellRun> runs = split_into_runs(index, threads);
  FamilyPass pass{&index, &options};
  const Buffer<std::int64_t> offsets = count_rows(pass, runs, threads);
  begin(offsets.data());
  Buffer<point_id> batch;
  for (std::size_t first = 0; first < n;) {
    const std::size_t last = batch_end(offsets.data(), n, first, batch_entries);
    const std::int64_t entries = offsets[last] - offsets[first];
    if (batch.size() < static_cast<std::size_t>(entries)) batch = Buffer<point_id>(static_cast<std::size_t>(entries));
    pass.indices = batch.data();
    pass.rows_begin = static_cast<point_id>(first);
    pass.rows_end = static_cast<point_id>(last);
    pass.indices_base = offsets[first];
    if (entries > 0) fill_rows(pass, runs, threads);
    rows(first, last, batch.data());
    first = last;
  }
}

}  // namespace horizon::detail
