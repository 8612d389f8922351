// The distance tests of count_families() and fill_families(), written once with highway and compiled for each
// instruction set (SSE4, AVX2, AVX-512, ...); the best one this CPU has is picked at run time,
// so a portable build runs at native speed everywhere. Neighbours are written with a register
// compress and a plain store: AVX-512's compress-store to memory is microcoded on AMD Zen 4/5.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/family_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/family_search.hpp"
#include "core/metric-inl.h"
#include "core/store_selected-inl.h"
#include "core/sort_network-inl.h"
#include "core/sorted_stencil.hpp"
#include "horizon/cell_index.hpp"


HWY_BEFORE_NAMESPACE();
namespace horizon::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Which candidates' ids a family excludes: those above `self` (half lists), `self` only, or
/// none (full lists whose caller removes `self` afterwards, which saves a compare per vector).
enum class IdTest { above_self, not_self, none };

/// TestCandidates (below) for T points at once (a tile of a cell's rows): each vector of
/// candidates is loaded once for all of them. found[t] += the neighbours of point t; Fill writes
/// them from out[t] + found[t]. (Sorted fill, lattice 10^6: 8-25 % faster at m = 3.015 on AMD Zen 5 and
/// Intel Xeon, 0-11 % at m = 1.5; bench/results/tiled_rows_1206.)
template <Metric M, int D, IdTest Ids, bool Fill, int T, bool OwnLimits = false, class V, class VI>
HWY_INLINE void TestTile(const V* px, const V* py, const V* pz, const VI* self, V threshold, const double* x,
                         const double* y, const double* z, const point_id* ids, std::int64_t begin,
                         std::int64_t end, point_id* const* out, std::int64_t* found,
                         const double* limits = nullptr) {
  const hn::DFromV<V> d;
  const hn::DFromV<VI> di;
  const auto lanes = static_cast<std::int64_t>(hn::Lanes(d));
  for (std::int64_t q = begin; q < end; q += lanes) {
    const V cx = hn::LoadU(d, x + q), cy = hn::LoadU(d, y + q);
    const V cz = D == 3 ? hn::LoadU(d, z + q) : cx;
    const VI candidate = hn::LoadU(di, ids + q);
    const V bound = OwnLimits ? hn::Min(threshold, hn::LoadU(d, limits + q)) : threshold;
    const unsigned valid = end - q < lanes ? (1u << (end - q)) - 1 : ~0u;
    for (int t = 0; t < T; ++t) {
      const V dx = hn::Sub(px[t], cx), dy = hn::Sub(py[t], cy);
      const V dz = D == 3 ? hn::Sub(pz[t], cz) : dx;
      // Masks cannot change lane size: combine the double and id lanes' masks as bits.
      std::uint8_t near[8], other[8] = {0xff};
      hn::StoreMaskBits(d, hn::Lt(accumulate<M, D>(dx, dy, dz), bound), near);
      if constexpr (Ids != IdTest::none)
        hn::StoreMaskBits(di, Ids == IdTest::above_self ? hn::Gt(candidate, self[t]) : hn::Ne(candidate, self[t]),
                          other);
      const unsigned keep = static_cast<unsigned>(near[0] & other[0]) & valid;
      if constexpr (Fill) StoreSelected(di, candidate, keep, out[t] + found[t]);
      found[t] += std::popcount(keep);
    }
  }
}

/// Tests point (px, py, pz) with id `self` against candidates [begin, end) of arrays x, y, z,
/// ids: a neighbour when within the horizon and passing `Ids`. Returns
/// their number; Fill also writes their ids to `out` in array order (and up to a vector of junk
/// after them). Loads may run up to a vector past `end` (the arrays are padded).
/// With OwnLimits, a candidate is a neighbour only below its own threshold limits[q] too.
template <Metric M, int D, IdTest Ids, bool Fill, bool OwnLimits = false, class V, class VI>
HWY_INLINE std::int64_t TestCandidates(V px, V py, V pz, VI self, V threshold, const double* x,
                                       const double* y, const double* z, const point_id* ids,
                                       std::int64_t begin, std::int64_t end, point_id* out,
                                       const double* limits = nullptr) {
  std::int64_t found = 0;
  TestTile<M, D, Ids, Fill, 1, OwnLimits>(&px, &py, &pz, &self, threshold, x, y, z, ids, begin, end, &out, &found,
                                          limits);
  return found;
}

/// SortShortRowTo compiled once per instruction set, not inlined into every pass variant (it
/// tripled the object's size and its build time under the sanitizers).
HWY_NOINLINE bool SortRowTo(const point_id* row, std::int64_t count, point_id drop, point_id* out, std::int64_t kept) {
  return SortShortRowTo(row, count, drop, out, kept);
}

/// Along one axis, the cells -low .. high from its own (`cell`, padding included) that can hold
/// neighbours of a point at t = (x - origin) * inverse_side (Grid::cell_of: cell = floor(t) + k)
/// with `reach` = its radius in cells. Every metric's distance is at least the difference along
/// one axis, so a cell is skipped only when its face is beyond the radius; the slack (far above
/// the rounding of t and of the radius) keeps it whenever one of its points could pass the test.
struct Reach {
  int low, high;
};
inline Reach ReachAlong(double t, std::int64_t cell, double reach, int k) {
  const double within = t - static_cast<double>(cell - k);  // in [0, 1)
  const double slack = 0x1p-30 * (1 + std::fabs(t)) + 0x1p-30 * reach;
  const double low = std::ceil(reach + slack - within), high = std::ceil(reach + slack + within) - 1;
  return {static_cast<int>(std::clamp(low, 0.0, static_cast<double>(k))),
          static_cast<int>(std::clamp(high, 0.0, static_cast<double>(k)))};
}

/// Calls f.template operator()<T>(start) for tiles of 4, 2 and 1 of `count` points, none
/// larger than `Largest`: each size is another copy of the loop in every pass variant.
template <int Largest = 4, class F>
HWY_INLINE void ForTiles(std::int64_t count, F&& f) {
  std::int64_t start = 0;
  if constexpr (Largest >= 4)
    for (; count - start >= 4; start += 4) f.template operator()<4>(start);
  if constexpr (Largest >= 2) {
    if (count - start >= 2) {
      f.template operator()<2>(start);
      start += 2;
    }
    if (count > start) f.template operator()<1>(start);
  } else {
    for (; start < count; ++start) f.template operator()<1>(start);
  }
}

/// Radii: pass.row_radius is set (compiled apart, so the one-horizon passes carry none of it).
template <Metric M, int D, IdTest Ids, bool Fill, bool Radii = false>
void VisitCells(const FamilyPass& pass, CellRun run) {
  using V = hn::Vec<hn::ScalableTag<double>>;
  const hn::ScalableTag<double> d;
  const hn::Rebind<point_id, decltype(d)> di;  // one id lane per coordinate lane
  using VI = hn::Vec<decltype(di)>;
  const auto lanes = static_cast<std::int64_t>(hn::Lanes(d));
  const CellIndex& index = *pass.index;
  const SearchOptions& options = *pass.options;
  const double *x = index.coords(0).data(), *y = index.coords(1).data(), *z = index.coords(2).data();
  const point_id* order = index.order().data();
  std::int64_t* offsets = pass.offsets;
  const std::size_t queries = options.queries ? options.queries : index.row_count();
  const auto points = static_cast<std::int64_t>(index.point_count());
  const double limit = metric_threshold(M, options.horizon);
  const auto threshold = hn::Set(d, limit);
  // With IdTest::none a family also holds `self` (distance 0), unless the threshold underflowed.
  const std::int64_t self_found = Ids == IdTest::none && limit > 0 ? 1 : 0;
  std::vector<CellIndex::Range> rows(static_cast<std::size_t>(index.max_stencil_rows()));
  SortedStencil sorted;
  // The fill finds a cell's rows a tile of up to `tile` points at a time, each vector of
  // candidates loaded once for the tile. Unsorted rows and half lists too: one at a time, each
  // row was read for its copy right after its last store and stalled on store forwarding (2-core
  // AMD Zen 5 VM, lattice 10^6, fill alone: m = 1.5 90 -> 59 ms unsorted, 94 -> 66-77 ms half;
  // bench/results/count_tiles_1206). The count pass of query subsets and per-point radii stays
  // one row at a time: tiles there too doubled this file's build time.
  constexpr int tile = Fill && !Radii ? 4 : 1;
  // Rows are found into `slots` buffers (up to `ring`, 32 KB), then sorted or copied to their
  // places all together once the buffers are full. Reading a row right after its ids were
  // stored stalled on store forwarding (the loads span several of the fill's compressed stores:
  // AMD Zen 5, rows of ~15 ids, 47 ns a row filled and sorted at once against 28 ns one row
  // later). And when the input is in no spatial order every row goes to a random place: those
  // stores, interleaved with the tests, stalled them (AMD Zen 5 VM, 10^6 points, m = 1.5, fill
  // alone: shuffled lattice 129-135 -> 100 ms, random cloud 131 -> 105-111 ms with 64 rows a
  // flush against one tile's; lattice order unchanged; bench/results/row_ring_1206). 32 KB: 64
  // rows at m = 1.5; 11 at m = 3.015, where 64 long rows gained nothing beyond the noise.
  constexpr int ring = Fill ? 64 : 1;
  int slots = ring;
  std::vector<point_id> row_buffers;  // `slots` rows, one allocation (a call per run of cells)
  std::size_t row_space = 0;
  auto row_buffer = [&](int slot) { return row_buffers.data() + slot * row_space; };
  struct Pending {
    const point_id* row = nullptr;
    std::int64_t count = 0;
    bool sort = false;       // by the network; else copied as it is
    bool drop_self = false;  // the row holds `self`, which the list does not
    point_id self = -1;
    point_id* place = nullptr;
  };
  Pending pending[ring];
  int pending_rows = 0;
  auto finish_pending = [&] {
    for (int t = 0; t < pending_rows; ++t) {
      const auto& [row, count, sort, drop_self, self, place] = pending[t];
      if (sort) {
        SortRowTo(row, count, drop_self ? self : point_id{-1}, place, count - drop_self);
      } else {  // around `self`, if present
        const std::int64_t before = drop_self ? std::lower_bound(row, row + count, self) - row : count;
        if (before > 0) std::memcpy(place, row, static_cast<std::size_t>(before) * sizeof(point_id));
        if (count > before + drop_self)
          std::memcpy(place + before, row + before + drop_self,
                      static_cast<std::size_t>(count - before - drop_self) * sizeof(point_id));
      }
    }
    pending_rows = 0;
  };
  auto make_room = [&](int rows) {
    if (pending_rows + rows > slots) finish_pending();
  };
  // Per-point radii: each row tests only the stencil's cells its radius reaches (a point whose
  // radius is a quarter of the class's largest meets about 3.4 of the 27 cells, k = 1). A row
  // longer than the sorting network is taken from the cell's sorted stencil instead.
  const int k = index.grid().cells_per_horizon, width = 2 * k + 1, kz = D == 3 ? k : 0;
  std::vector<CellIndex::Range> cells(Radii ? static_cast<std::size_t>(index.max_stencil_cells()) : 0);
  constexpr std::int64_t short_row = ShortRowCapacity<point_id>();
  // Whether the row of point `self` (its counted size, plus `self` when the pass finds it) is
  // longer than the sorting network holds.
  auto beyond_network = [&](point_id self, std::int64_t with_self) {
    return offsets[self + 1] - offsets[self] + with_self > short_row;
  };
  constexpr std::int64_t lookahead = 16;

  // A batch of rows (FamilyPass::rows_begin..rows_end) fills only the cells holding one of its points.
  const point_id rows_begin = pass.rows_begin, rows_end = pass.rows_end;
  const bool all_rows = rows_begin == 0 && static_cast<std::size_t>(rows_end) >= index.row_count();
  auto in_batch = [&](point_id id) { return id >= rows_begin && id < rows_end; };
  const std::int64_t base = pass.indices_base;

  // The row of `self`, `found` ids long (with `self` when `with_self`): counted, or, found into
  // the next free buffer, queued to be sorted (`sorted`: it already is) and put in its place.
  auto finish_row = [&](point_id self, std::int64_t found, bool sorted, std::int64_t with_self) {
    if constexpr (Fill) {
      point_id* const row = row_buffer(pending_rows);
      // Sorted in registers by a network, `self` dropped, straight to its place; a longer row
      // (rare: the stencil is sorted from 256 candidates) by insertion, then copied.
      // Insertion mispredicts a branch per move on rows in no order: AMD Zen 5, m = 1.5,
      // shuffled lattice 0.36-0.39 s to fill, 0.19-0.24 s with the network.
      const bool to_sort = options.sort_rows && !sorted, network = to_sort && found <= short_row;
      if (to_sort && !network) insertion_sort(row, row + found);
      pending[pending_rows++] = {row, found, network, with_self != 0, self, pass.indices + (offsets[self] - base)};
      if (pass.found) pass.found[self] = found - with_self;
    } else {
      offsets[self + 1] = found - with_self;
    }
  };

  for (std::size_t c = run.first; c < run.last; ++c) {
    // A cell of periodic images only (the shell outside the box) has no rows: no stencil to list.
    if (const CellIndex::Range own = index.rows_of(c); own.begin == own.end) continue;
    if constexpr (Fill)
      if (!all_rows) {
        const auto [first, last] = index.rows_of(c);
        if (std::none_of(order + first, order + last, in_batch)) continue;
      }
    if constexpr (Radii) {  // only the cells holding a point with a row here
      const auto [first, last] = index.rows_of(c);
      if (std::none_of(pass.row_radius + first, pass.row_radius + last, [](double r) { return r > 0; })) continue;
    }
    const int row_count = index.stencil(c, rows.data());
    std::int64_t candidates = 0;
    for (int r = 0; r < row_count; ++r) candidates += rows[r].end - rows[r].begin;
    // Padded for the vector stores of TestCandidates and the loads of SortShortRowTo.
    const std::int64_t row_padding = lanes + static_cast<std::int64_t>(hn::MaxLanes(hn::ScalableTag<point_id>()));
    if (Fill && row_space < static_cast<std::size_t>(candidates + row_padding)) {
      finish_pending();
      row_space = static_cast<std::size_t>(candidates + row_padding);
      const std::size_t fit = (std::size_t{32} << 10) / (row_space * sizeof(point_id));
      slots = static_cast<int>(std::clamp(fit, std::size_t{2} * tile, std::size_t{ring}));
      row_buffers.resize(static_cast<std::size_t>(slots) * row_space);
    }
    // Sorted rows: one by one in registers by the network when every row of the cell fits it
    // (m = 1.5: 18 ids; m = 3.015: 118, within AVX-512's 128), else from the stencil sorted once
    // per cell (a large one: a small stencil costs more to sort than its rows).
    bool sorted_stencil = false;
    if (Fill && !Radii && options.sort_rows && candidates >= 256) {
      const auto [first, last] = index.rows_of(c);
      for (std::int64_t p = first; p < last && !sorted_stencil; ++p) {
        const point_id self = order[p];
        sorted_stencil = static_cast<std::size_t>(self) < queries && beyond_network(self, self_found);
      }
    }
    bool gathered = false;
    auto gather = [&] {
      if (!gathered) sorted.gather(index, c);
      gathered = true;
    };
    if (sorted_stencil) gather();
    if constexpr (Radii) index.stencil_cells(c, cells.data());
    const auto& cell = index.cell_coord(c);  // (cz, cy, cx)

    // The rows of the tile's points (sorted positions), against the stencil's runs of cells or
    // the sorted stencil, one run.
    const CellIndex::Range whole{0, sorted_stencil ? sorted.size() : 0};
    const CellIndex::Range* const runs = sorted_stencil ? &whole : rows.data();
    const int run_count = sorted_stencil ? 1 : row_count;
    const double* const from[3] = {sorted_stencil ? sorted.coords(0) : x, sorted_stencil ? sorted.coords(1) : y,
                                   sorted_stencil ? sorted.coords(2) : z};
    const point_id* const from_ids = sorted_stencil ? sorted.ids() : order;
    std::int64_t members[tile];
    int size = 0;
    auto test_tile = [&]<int T>(std::int64_t start) {
      V px[T], py[T], pz[T];
      VI ids[T];
      point_id* out[T];
      std::int64_t found[T] = {};
      if constexpr (Fill) make_room(T);
      for (int t = 0; t < T; ++t) {
        const std::int64_t p = members[start + t];
        px[t] = hn::Set(d, x[p]), py[t] = hn::Set(d, y[p]), pz[t] = hn::Set(d, z[p]);
        ids[t] = hn::Set(di, order[p]);
        out[t] = Fill ? row_buffer(pending_rows + t) : nullptr;
      }
      for (int r = 0; r < run_count; ++r)
        TestTile<M, D, Ids, Fill, T>(px, py, pz, ids, threshold, from[0], from[1], from[2], from_ids, runs[r].begin,
                                     runs[r].end, out, found);
      for (int t = 0; t < T; ++t) finish_row(order[members[start + t]], found[t], sorted_stencil, self_found);
    };
    auto flush_tile = [&] {
      if constexpr (!Radii) ForTiles<tile>(size, test_tile);
      size = 0;
    };

    const auto [first, last] = index.rows_of(c);
    for (std::int64_t p = first; p < last; ++p) {
      const point_id self = order[p];
      // Rows are placed by input id: for input in random order every point's row (and its
      // offset) is a cache miss. Fetch them a few points ahead (measured: the fill pass on a
      // random cloud of 10^6 points, m = 1.5, went from 0.69 s to 0.39 s).
      if (p + 2 * lookahead < points) __builtin_prefetch(&offsets[order[p + 2 * lookahead]]);
      if constexpr (Fill)
        if (p + lookahead < points && in_batch(order[p + lookahead]))
          __builtin_prefetch(pass.indices + (offsets[order[p + lookahead]] - base));
      if (static_cast<std::size_t>(self) >= queries) continue;  // no family: size stays 0
      if (Fill && !in_batch(self)) continue;
      if constexpr (!Radii) {
        members[size++] = p;
        if (size == tile) flush_tile();
        continue;
      }
      // Per-point radii: this row's own threshold, or no row; one row at a time.
      const double radius = pass.row_radius[p];
      if (!(radius > 0)) continue;
      const double row_limit = metric_threshold(M, radius);
      const auto row_threshold = hn::Set(d, row_limit);
      const std::int64_t row_self_found = Ids == IdTest::none && row_limit > 0 ? 1 : 0;
      const auto px = hn::Set(d, x[p]), py = hn::Set(d, y[p]), pz = hn::Set(d, z[p]);
      const auto id = hn::Set(di, self);
      if constexpr (Fill) make_room(1);
      point_id* const row = Fill ? row_buffer(pending_rows) : nullptr;
      std::int64_t found = 0;
      const bool sorted_row = Fill && options.sort_rows && !pass.candidate_threshold &&
                              beyond_network(self, row_self_found);
      if (sorted_row) {
        gather();
        found = TestCandidates<M, D, Ids, Fill>(px, py, pz, id, row_threshold, sorted.coords(0), sorted.coords(1),
                                                 sorted.coords(2), sorted.ids(), 0, sorted.size(), row);
      } else {
        const Grid& grid = index.grid();
        const double reach = radius * grid.inverse_side;
        Reach along[3] = {{0, 0}, {0, 0}, {0, 0}};
        for (int a = 0; a < D; ++a) {
          const double coordinate = a == 0 ? x[p] : a == 1 ? y[p] : z[p];
          along[a] = ReachAlong((coordinate - grid.origin[static_cast<std::size_t>(a)]) * grid.inverse_side,
                                cell[static_cast<std::size_t>(2 - a)], reach, k);
        }
        for (int dz = -along[2].low; dz <= along[2].high; ++dz)
          for (int dy = -along[1].low; dy <= along[1].high; ++dy) {
            const CellIndex::Range* columns = cells.data() + ((dz + kz) * width + dy + k) * width + k;
            const std::int64_t begin = columns[-along[0].low].begin, end = columns[along[0].high].end;
            if (begin >= end) continue;
            point_id* const out = Fill ? row + found : nullptr;
            if (pass.candidate_threshold)
              found += TestCandidates<M, D, Ids, Fill, true>(px, py, pz, id, row_threshold, x, y, z, order, begin,
                                                              end, out, pass.candidate_threshold);
            else
              found += TestCandidates<M, D, Ids, Fill>(px, py, pz, id, row_threshold, x, y, z, order, begin, end, out);
          }
      }
      finish_row(self, found, sorted_row, row_self_found);
    }
    if constexpr (!Radii) flush_tile();
  }
  if constexpr (Fill) finish_pending();
}

/// The count pass with each pair tested once (one point set, one horizon, no images): a point
/// tests the points after it in its cell and those of the cell's upper stencil
/// (CellIndex::upper_stencil), and a hit counts for both points (half lists: for the lower id
/// only). Row point minus candidate, as in the fill: d(i, j) and d(j, i) are equal bit for bit.

/// Tests a tile of T points (px[t], py[t], pz[t], ids self[t]) against the candidates of
/// [begin, end) of x, y, z, ids that come after position after[t] (in its own cell, the points
/// after it; elsewhere every one). found[t] -= the hits that count for point t, gained[q] -=
/// those that count for candidate q (VecFromMask is -1 per hit). Each vector of candidates and
/// of their counts is loaded once for the tile, not once per point. The vectors start on the
/// same lanes for every tile of a cell (a vector of counts stored for one tile is loaded whole
/// for the next), and no lane past `end` is stored (another thread's to write).
template <Metric M, int D, bool Half, int T, class V, class VC>
HWY_INLINE void CountTile(const V* px, const V* py, const V* pz, const VC* self, const std::int64_t* after,
                          V threshold, const double* x, const double* y, const double* z, const point_id* ids,
                          std::int64_t begin, std::int64_t end, std::int64_t* gained, VC* found) {
  const hn::DFromV<V> d;
  const hn::DFromV<VC> dc;
  const hn::Rebind<point_id, decltype(d)> di;
  const auto lanes = static_cast<std::int64_t>(hn::Lanes(d));
  if (after[0] >= begin) begin += (after[0] + 1 - begin) / lanes * lanes;  // after[0] is the tile's least
  VC first[T];
  for (int t = 0; t < T; ++t) first[t] = hn::Set(dc, after[t]);
  const auto lane = hn::Iota(dc, 0), stop = hn::Set(dc, end);
  for (std::int64_t q = begin; q < end; q += lanes) {
    const V cx = hn::LoadU(d, x + q), cy = hn::LoadU(d, y + q);
    const V cz = D == 3 ? hn::LoadU(d, z + q) : cx;
    const VC position = hn::Add(hn::Set(dc, q), lane);
    const auto inside = hn::Lt(position, stop);
    VC candidate = hn::Zero(dc);
    if constexpr (Half) candidate = hn::PromoteTo(dc, hn::LoadU(di, ids + q));
    VC updated = hn::LoadU(dc, gained + q);
    for (int t = 0; t < T; ++t) {
      const V dx = hn::Sub(px[t], cx), dy = hn::Sub(py[t], cy);
      const V dz = D == 3 ? hn::Sub(pz[t], cz) : dx;
      auto hits = hn::And(hn::RebindMask(dc, hn::Lt(accumulate<M, D>(dx, dy, dz), threshold)),
                          hn::And(hn::Gt(position, first[t]), inside));
      auto theirs = hits;
      if constexpr (Half) {
        const auto above = hn::Gt(candidate, self[t]);
        theirs = hn::AndNot(above, hits);
        hits = hn::And(hits, above);
      }
      found[t] = hn::Add(found[t], hn::VecFromMask(dc, hits));
      updated = hn::Sub(updated, hn::VecFromMask(dc, theirs));
    }
    if (end - q < lanes) hn::BlendedStore(updated, inside, dc, gained + q);
    else hn::StoreU(updated, dc, gained + q);
  }
}

/// counts[q] += the family size of the point at sorted position q, for each pair met from the
/// cells of `run`, a tile of up to four of a cell's points at a time (count pass alone, 2-core
/// AMD Zen 5 VM, lattice 10^6: 28 % faster at m = 1.5, 18 % at m = 3.015, with AVX-512 and AVX2;
/// bench/results/count_tiles_1206). A cell with a large upper stencil (m = 3.015: ~350 candidates)
/// gathers it into one run first, and adds the counts it gained back at the end: one loop per
/// tile instead of one per row of cells. Small stencils (m = 1.5: ~40) cost more to gather than
/// their rows' loop exits. (2-core AMD Zen 3 VM, lattice and random 10^6, count pass alone:
/// 1.2-1.4x the count over every stencil at m = 1.5, 1.3-1.8x at m = 3.015.)
template <Metric M, int D, bool Half>
void CountPairs(const FamilyPass& pass, CellRun run, std::int64_t* counts) {
  constexpr std::int64_t gather_from = 128;
  using V = hn::Vec<hn::ScalableTag<double>>;
  const hn::ScalableTag<double> d;
  const hn::RebindToSigned<decltype(d)> dc;  // counts: one 64-bit lane per coordinate lane
  using VC = hn::Vec<decltype(dc)>;
  const auto lanes = static_cast<std::int64_t>(hn::Lanes(d));
  const CellIndex& index = *pass.index;
  const double* coords[3] = {index.coords(0).data(), index.coords(1).data(), index.coords(2).data()};
  const point_id* order = index.order().data();
  const auto threshold = hn::Set(d, metric_threshold(M, pass.options->horizon));
  std::vector<CellIndex::Range> rows(static_cast<std::size_t>(index.max_stencil_rows()));
  std::vector<double> gathered[3];
  std::vector<point_id> gathered_ids;
  std::vector<std::int64_t> gained;
  for (std::size_t c = run.first; c < run.last; ++c) {
    const int row_count = index.upper_stencil(c, rows.data());
    std::int64_t size = 0;
    for (int r = 0; r < row_count; ++r) size += rows[r].end - rows[r].begin;
    const auto [first, last] = index.points_of(c);
    const bool gather = size >= gather_from;
    if (gather) {
      const auto padded = static_cast<std::size_t>(size + lanes);
      if (gained.size() < padded) {
        for (auto& axis : gathered) axis.resize(padded);
        gathered_ids.resize(padded);
        gained.resize(padded);
      }
      std::int64_t at = 0;  // the cell's own points come first
      for (int r = 0; r < row_count; ++r) {
        const auto length = static_cast<std::size_t>(rows[r].end - rows[r].begin);
        for (int a = 0; a < D; ++a)
          std::memcpy(gathered[a].data() + at, coords[a] + rows[r].begin, length * sizeof(double));
        if (Half) std::memcpy(gathered_ids.data() + at, order + rows[r].begin, length * sizeof(point_id));
        at += static_cast<std::int64_t>(length);
      }
      std::fill_n(gained.begin(), padded, 0);
    }
    // Positions [0, size) of the gathered stencil, or the cell's own from `first` on.
    const std::int64_t base = gather ? 0 : first;
    const double* const x = gather ? gathered[0].data() : coords[0];
    const double* const y = gather ? gathered[1].data() : coords[1];
    const double* const z = gather ? gathered[2].data() : coords[2];
    const point_id* const ids = gather ? gathered_ids.data() : order;
    std::int64_t* const tally = gather ? gained.data() : counts;
    // Inlined by force: called apart, the tile's vectors live in memory that every store of
    // counts may alias (vector types may alias anything), so they were reloaded after each one;
    // 30 % slower than the one-point loop before at m = 1.5.
    auto count_tile = [&]<int T>(std::int64_t start) __attribute__((always_inline)) {
      V px[T], py[T], pz[T];
      VC self[T], found[T];
      std::int64_t after[T];
      for (int t = 0; t < T; ++t) {
        const std::int64_t p = base + start + t;
        px[t] = hn::Set(d, x[p]);
        py[t] = hn::Set(d, y[p]);
        pz[t] = hn::Set(d, D == 3 ? z[p] : 0.0);
        self[t] = hn::Set(dc, order[first + start + t]);
        found[t] = hn::Zero(dc);
        after[t] = p;
      }
      if (gather) {
        CountTile<M, D, Half, T>(px, py, pz, self, after, threshold, x, y, z, ids, 0, size, tally, found);
      } else {
        CountTile<M, D, Half, T>(px, py, pz, self, after, threshold, x, y, z, ids, rows[0].begin, rows[0].end,
                                 tally, found);
        for (int r = 1; r < row_count; ++r) {
          for (int t = 0; t < T; ++t) after[t] = rows[r].begin - 1;
          CountTile<M, D, Half, T>(px, py, pz, self, after, threshold, x, y, z, ids, rows[r].begin, rows[r].end,
                                   tally, found);
        }
      }
      for (int t = 0; t < T; ++t) tally[base + start + t] -= hn::GetLane(hn::SumOfLanes(dc, found[t]));
    };
    ForTiles(last - first, count_tile);
    if (gather) {
      std::int64_t at = 0;
      for (int r = 0; r < row_count; ++r)
        for (std::int64_t q = rows[r].begin; q < rows[r].end; ++q) counts[q] += gained[static_cast<std::size_t>(at++)];
    }
  }
}

template <Metric M>
void CountPairsIn(const FamilyPass& pass, CellRun run, std::int64_t* counts) {
  const bool three = pass.index->grid().dims == 3;
  if (pass.options->half)
    three ? CountPairs<M, 3, true>(pass, run, counts) : CountPairs<M, 2, true>(pass, run, counts);
  else
    three ? CountPairs<M, 3, false>(pass, run, counts) : CountPairs<M, 2, false>(pass, run, counts);
}

void CountEachPairOnce(const FamilyPass& pass, CellRun run, std::int64_t* counts) {
  switch (pass.options->metric) {
    case Metric::euclidean: return CountPairsIn<Metric::euclidean>(pass, run, counts);
    case Metric::manhattan: return CountPairsIn<Metric::manhattan>(pass, run, counts);
    case Metric::chebyshev: return CountPairsIn<Metric::chebyshev>(pass, run, counts);
  }
}

template <bool Fill, Metric M, int D>
void VisitHalf(const FamilyPass& pass, CellRun run) {
  // Full lists drop `self` after the tests where the row is sorted (or only counted), so its
  // place is found by a binary search.
  if (pass.row_radius)  // full sorted rows, each within its own radius
    VisitCells<M, D, IdTest::none, Fill, true>(pass, run);
  else if (pass.options->half)
    VisitCells<M, D, IdTest::above_self, Fill>(pass, run);
  else if (!Fill || pass.options->sort_rows)
    VisitCells<M, D, IdTest::none, Fill>(pass, run);
  else
    VisitCells<M, D, IdTest::not_self, Fill>(pass, run);
}

template <bool Fill, Metric M>
void VisitDims(const FamilyPass& pass, CellRun run) {
  if (pass.index->grid().dims == 3)
    VisitHalf<Fill, M, 3>(pass, run);
  else
    VisitHalf<Fill, M, 2>(pass, run);
}

template <bool Fill>
void VisitMetric(const FamilyPass& pass, CellRun run) {
  switch (pass.options->metric) {
    case Metric::euclidean: return VisitDims<Fill, Metric::euclidean>(pass, run);
    case Metric::manhattan: return VisitDims<Fill, Metric::manhattan>(pass, run);
    case Metric::chebyshev: return VisitDims<Fill, Metric::chebyshev>(pass, run);
  }
}

void CountFamilies(const FamilyPass& pass, CellRun run) { VisitMetric<false>(pass, run); }
void FillFamilies(const FamilyPass& pass, CellRun run) { VisitMetric<true>(pass, run); }

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace horizon::detail {

HWY_EXPORT(CountFamilies);
HWY_EXPORT(FillFamilies);
HWY_EXPORT(CountEachPairOnce);
HWY_EXPORT(TargetName);

void count_families(const FamilyPass& pass, CellRun run) { HWY_DYNAMIC_DISPATCH(CountFamilies)(pass, run); }
void fill_families(const FamilyPass& pass, CellRun run) { HWY_DYNAMIC_DISPATCH(FillFamilies)(pass, run); }
void count_each_pair_once(const FamilyPass& pass, CellRun run, std::int64_t* counts) {
  HWY_DYNAMIC_DISPATCH(CountEachPairOnce)(pass, run, counts);
}

const char* simd_target() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

}  // namespace horizon::detail
#endif
