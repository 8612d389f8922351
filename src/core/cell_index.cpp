#include "horizon/cell_index.hpp"

#include <algorithm>
#include <bit>
#include <utility>
#include <limits>
#include <numeric>

#include <parallel/algorithm>

#include "parallel_for.hpp"
#include "parallel_scan.hpp"
#include "radix_sort.hpp"

namespace horizon {

namespace {

template <class Coordinate>
std::array<std::int64_t, 3> cell_of_point(const Coordinate& coordinate, const Grid& grid, std::size_t i) {
  std::array<std::int64_t, 3> c{0, 0, 0};
  for (int a = 0; a < grid.dims; ++a) c[a] = grid.cell_of(coordinate(i, a), a);
  return c;
}

/// Coordinate `a` of point i of an index: the points (D coordinates of type T each) first, then
/// the images. Typed, so that the loops over every point compile without a branch on the type
/// (the serial cell sort took 15 ms for 10^6 points through PointView, Intel Xeon host).
template <class T, int D>
struct IndexPoints {
  const T* xyz;
  std::size_t rows;
  PointView images;
  void prefetch(std::size_t i) const {
    if (i < rows) __builtin_prefetch(xyz + i * D);
  }
  double operator()(std::size_t i, int a) const {
    return i < rows ? static_cast<double>(xyz[i * D + static_cast<std::size_t>(a)]) : images(i - rows, a);
  }
};

}  // namespace

CellIndex::CellIndex(PointView points, const Grid& grid, int threads, Images images)
    : grid_(grid), count_(points.size() + images.points.size()), rows_(points.size()) {
  const bool single = points.is_float32(), flat = points.dims() == 2;
  if (single && flat) build(IndexPoints<float, 2>{points.float32_data(), rows_, images.points}, threads, images);
  if (single && !flat) build(IndexPoints<float, 3>{points.float32_data(), rows_, images.points}, threads, images);
  if (!single && flat) build(IndexPoints<double, 2>{points.float64_data(), rows_, images.points}, threads, images);
  if (!single && !flat) build(IndexPoints<double, 3>{points.float64_data(), rows_, images.points}, threads, images);
}

template <class Coordinate>
void CellIndex::build(const Coordinate& coordinate, int threads, Images images) {
  // Written in full below; only the padding is set here (zeroing first cost a serial pass).
  order_.resize(count_ + padding);
  std::fill(order_.begin() + static_cast<std::ptrdiff_t>(count_), order_.end(), -1);
  if (grid_.dense) {
    sort_dense(coordinate, threads);
  } else {
    sort_sparse(coordinate, threads);
    index_rows();
  }
  cell_begin_.push_back(static_cast<std::int64_t>(count_));

  const auto n = static_cast<std::int64_t>(count_);
  for (auto& axis : sorted_) {
    axis.resize(count_ + padding);
    std::fill(axis.begin() + static_cast<std::ptrdiff_t>(count_), axis.end(), std::numeric_limits<double>::quiet_NaN());
  }
  // Images: a cell's rows end at its first image (the sort is stable, images come last), and
  // each image takes the id of the point it copies.
  const auto rows = static_cast<point_id>(rows_);
  if (!images.points.empty()) {
    const auto cells = static_cast<std::int64_t>(occupied_cells());
    cell_rows_end_.resize(static_cast<std::size_t>(cells));
    detail::parallel_for(cells, threads, [&](std::int64_t c) {
      // Back from the cell's end over its images: most cells hold none, so this is one
      // predictable test where a binary search mispredicted (3 % of a periodic search).
      std::int64_t end = cell_begin_[c + 1];
      while (end > cell_begin_[c] && order_[static_cast<std::size_t>(end - 1)] >= rows) --end;
      cell_rows_end_[c] = end;
    });
  }
  detail::parallel_for(n, threads, [&](std::int64_t p) {
    // Input in random order: each point's coordinates are a cache miss; fetch them ahead
    // (random cloud of 10^6, one core of the 2-core Zen 5 VM: cell index 25-26 -> 22-23 ms).
    if (p + 16 < n) coordinate.prefetch(static_cast<std::size_t>(order_[p + 16]));
    const point_id i = order_[p];
    for (int a = 0; a < 3; ++a)
      sorted_[a][static_cast<std::size_t>(p)] = a < grid_.dims ? coordinate(static_cast<std::size_t>(i), a) : 0.0;
    if (i >= rows) order_[p] = images.image_of[static_cast<std::size_t>(i - rows)];
  });
}

// Points by linear cell id, stable, so a cell's points are ascending by input id whatever the
// thread count. One thread: a counting sort (thesis §4.2.3): count, exclusive scan, place.
// Several: a radix sort of (cell, point) keys, whose runs of equal cells give the table.
template <class Coordinate>
void CellIndex::sort_dense(const Coordinate& coordinate, int threads) {
  const auto n = static_cast<std::int64_t>(count_);
  const auto cells = static_cast<std::int64_t>(grid_.cell_count());
  start_by_id_.resize(static_cast<std::size_t>(cells) + 1);  // every entry is written below
  std::int64_t* start = start_by_id_.data();
  auto cell_id = [&](std::int64_t i) {
    const auto c = cell_of_point(coordinate, grid_, static_cast<std::size_t>(i));
    return grid_.linear_id(c[0], c[1], c[2]);
  };
  if (threads > 1 && cells <= std::int64_t{1} << 32) {
    ScratchBuffer<std::uint64_t> keys(count_);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t i = 0; i < n; ++i) keys[i] = static_cast<std::uint64_t>(cell_id(i)) << 32 | static_cast<std::uint64_t>(i);
    detail::radix_sort_high_word(keys, std::bit_width(static_cast<std::uint64_t>(cells - 1)), threads);
    // Sorted position p starts the cells after its predecessor's, up to its own.
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t p = 0; p <= n; ++p) {
      const std::int64_t cell = p < n ? static_cast<std::int64_t>(keys[p] >> 32) : cells;
      const std::int64_t before = p > 0 ? static_cast<std::int64_t>(keys[p - 1] >> 32) : -1;
      for (std::int64_t c = before + 1; c <= cell; ++c) start[c] = p;
      if (p < n) order_[p] = static_cast<point_id>(keys[p] & 0xffffffffu);
    }
  } else {
    ScratchBuffer<std::int64_t> id(count_);
    std::fill(start_by_id_.begin(), start_by_id_.end(), 0);
    for (std::int64_t i = 0; i < n; ++i) ++start[(id[i] = cell_id(i)) + 1];
    detail::inclusive_scan(start, start_by_id_.size(), 1);
    ScratchBuffer<std::int64_t> next(start_by_id_.begin(), start_by_id_.end() - 1);
    for (std::int64_t i = 0; i < n; ++i) order_[next[id[i]]++] = static_cast<point_id>(i);
  }

  // Occupied cells: the non-empty entries of the table, x fastest, as in the sort; counted per
  // block of the table, then written in block order.
  const std::int64_t blocks = std::max(1, threads) * 4;
  std::vector<std::int64_t> occupied(static_cast<std::size_t>(blocks) + 1, 0);
  auto block_cells = [&](std::int64_t b) { return std::pair{cells * b / blocks, cells * (b + 1) / blocks}; };
  detail::parallel_for(blocks, threads, [&](std::int64_t b) {
    const auto [first, last] = block_cells(b);
    for (std::int64_t c = first; c < last; ++c) occupied[b + 1] += start[c + 1] > start[c];
  });
  detail::inclusive_scan(occupied.data(), occupied.size(), 1);
  cell_begin_.resize(static_cast<std::size_t>(occupied.back()));
  cell_coord_.resize(cell_begin_.size());
  detail::parallel_for(blocks, threads, [&](std::int64_t b) {
    const auto [first, last] = block_cells(b);
    std::int64_t out = occupied[b];
    // The cell's coordinates stepped along with it: a division per cell cost more than the rest.
    const std::int64_t nx = grid_.cells[0], ny = grid_.cells[1];
    std::int64_t cx = first % nx, cy = first / nx % ny, cz = first / (nx * ny);
    for (std::int64_t c = first; c < last; ++c) {
      if (start[c + 1] != start[c]) {
        cell_coord_[out] = {cz, cy, cx};
        cell_begin_[out++] = start[c];
      }
      if (++cx == nx) {
        cx = 0;
        if (++cy == ny) cy = 0, ++cz;
      }
    }
  });
}

// Sparse: points sorted by (cz, cy, cx, id); memory stays O(N) whatever the extent. When every
// axis has at most 2^32 cells (any extent short of 2^32 horizons), by stable radix sorts of
// (cell coordinate, point) keys along x, then y, then z, on every thread; else (and for the
// runs' order this is the same) by a merge sort of the points. A comparison sort of (cz, cy,
// cx, id) tuples took 0.18 s for 10^6 points on one thread, against 0.02 s for a dense grid.
template <class Coordinate>
void CellIndex::sort_sparse(const Coordinate& coordinate, int threads) {
  const auto n = static_cast<std::int64_t>(count_);
  ScratchBuffer<std::array<std::int64_t, 3>> cell(count_);  // each point's (cz, cy, cx)
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto c = cell_of_point(coordinate, grid_, static_cast<std::size_t>(i));
    cell[static_cast<std::size_t>(i)] = {c[2], c[1], c[0]};
  }
  const bool narrow = std::all_of(grid_.cells.begin(), grid_.cells.end(), [](std::int64_t c) { return c <= std::int64_t{1} << 32; });
  if (narrow) {
    ScratchBuffer<std::uint64_t> keys(count_);
    for (int axis = 0; axis < grid_.dims; ++axis) {
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
      for (std::int64_t p = 0; p < n; ++p) {
        const std::uint64_t point = axis == 0 ? static_cast<std::uint64_t>(p) : keys[p] & 0xffffffffu;
        keys[p] = static_cast<std::uint64_t>(cell[point][static_cast<std::size_t>(2 - axis)]) << 32 | point;
      }
      detail::radix_sort_high_word(keys, std::bit_width(static_cast<std::uint64_t>(grid_.cells[axis] - 1)), threads);
    }
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
    for (std::int64_t p = 0; p < n; ++p) order_[p] = static_cast<point_id>(keys[p] & 0xffffffffu);
  } else {
    auto before = [&](point_id a, point_id b) {
      return std::pair{cell[static_cast<std::size_t>(a)], a} < std::pair{cell[static_cast<std::size_t>(b)], b};
    };
    std::iota(order_.begin(), order_.begin() + n, point_id{0});
    __gnu_parallel::sort(order_.begin(), order_.begin() + n, before,
                         __gnu_parallel::multiway_mergesort_tag(static_cast<__gnu_parallel::_ThreadIndex>(threads)));
  }
  for (std::size_t p = 0; p < count_; ++p) {
    const std::array<std::int64_t, 3>& c = cell[static_cast<std::size_t>(order_[p])];
    // Compared axis by axis: array != compiled to a memcmp call, a fifth of the sort's time.
    if (p == 0 || c[0] != cell_coord_.back()[0] || c[1] != cell_coord_.back()[1] || c[2] != cell_coord_.back()[2]) {
      cell_coord_.push_back(c);
      cell_begin_.push_back(static_cast<std::int64_t>(p));
    }
  }
}

namespace {

std::uint64_t row_hash(std::int64_t cy, std::int64_t cz) {
  std::uint64_t h = static_cast<std::uint64_t>(cz) * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(cy);
  h = (h ^ (h >> 31)) * 0xBF58476D1CE4E5B9ull;
  return h ^ (h >> 29);
}

}  // namespace

// A sparse grid's stencils look rows of cells up by (cy, cz), and a row's run by column: a
// binary search over every occupied cell took about 20 cache misses a lookup (clustered cloud
// of 10^6 points and one far outlier, k = 2: 2.5-2.7 s to search, against 0.57 s for the same
// points in a dense grid). Now a hash table finds the row, and a row spanning at most
// `table_span` columns per occupied cell has a table of its columns (O(N) in all).
void CellIndex::index_rows() {
  constexpr std::int64_t table_span = 16;
  std::size_t occupied = 0;
  for (std::size_t c = 0; c < cell_coord_.size(); ++c)
    occupied += c == 0 || cell_coord_[c][0] != cell_coord_[c - 1][0] || cell_coord_[c][1] != cell_coord_[c - 1][1];
  occupied_rows_.assign(std::bit_ceil(2 * occupied + 1), OccupiedRow{0, 0, -1, -1, 0, 0, -1});
  column_start_.clear();
  for (std::size_t c = 0; c < cell_coord_.size();) {
    const auto [cz, cy, cx] = cell_coord_[c];
    std::size_t end = c + 1;
    while (end < cell_coord_.size() && cell_coord_[end][0] == cz && cell_coord_[end][1] == cy) ++end;
    OccupiedRow row{cz, cy, static_cast<std::int64_t>(c), static_cast<std::int64_t>(end), cx, cell_coord_[end - 1][2], -1};
    if (row.high_x - row.low_x < table_span * (row.end - row.first)) {
      row.table = static_cast<std::int64_t>(column_start_.size());
      for (std::size_t at = c; at < end; ++at)
        column_start_.resize(static_cast<std::size_t>(row.table + cell_coord_[at][2] - row.low_x) + 1, cell_begin_[at]);
    }
    occupied_rows_[row_slot(cy, cz)] = row;
    c = end;
  }
}

std::size_t CellIndex::row_slot(std::int64_t cy, std::int64_t cz) const {
  const std::size_t mask = occupied_rows_.size() - 1;
  for (std::size_t slot = row_hash(cy, cz) & mask;; slot = (slot + 1) & mask) {
    const OccupiedRow& row = occupied_rows_[slot];
    if (row.first < 0 || (row.cz == cz && row.cy == cy)) return slot;
  }
}

int CellIndex::max_stencil_rows() const {
  const int width = 2 * grid_.cells_per_horizon + 1;
  return grid_.dims == 3 ? width * width : width;
}

CellIndex::Range CellIndex::sparse_row(std::int64_t x_first, std::int64_t x_last, std::int64_t cy,
                                       std::int64_t cz) const {
  // An empty row: one empty run for every cell of it.
  const OccupiedRow& cells = occupied_row(cy, cz);
  if (cells.first < 0) return {0, 0};
  return {column_start(cells, x_first), column_start(cells, x_last + 1)};
}

// From the row's table, else by a binary search of its cells.
std::int64_t CellIndex::column_start(const OccupiedRow& row, std::int64_t x) const {
  if (x <= row.low_x) return cell_begin_[static_cast<std::size_t>(row.first)];
  if (x > row.high_x) return cell_begin_[static_cast<std::size_t>(row.end)];
  if (row.table >= 0) return column_start_[static_cast<std::size_t>(row.table + x - row.low_x)];
  const auto at = std::lower_bound(cell_coord_.begin() + row.first, cell_coord_.begin() + row.end, x,
                                   [](const std::array<std::int64_t, 3>& cell, std::int64_t v) { return cell[2] < v; });
  return cell_begin_[static_cast<std::size_t>(at - cell_coord_.begin())];
}

int CellIndex::stencil(std::size_t c, Range* out) const {
  const std::int64_t k = grid_.cells_per_horizon;
  return stencil_columns(c, -k, k, out);
}

int CellIndex::stencil_columns(std::size_t c, std::int64_t first, std::int64_t last, Range* out) const {
  const std::int64_t k = grid_.cells_per_horizon;
  const std::int64_t reach_z = grid_.dims == 3 ? k : 0;
  const auto [cz, cy, cx] = cell_coord_[c];
  int rows = 0;
  for (std::int64_t dz = -reach_z; dz <= reach_z; ++dz)
    for (std::int64_t dy = -k; dy <= k; ++dy) {
      const Range r = row(cx + first, cx + last, cy + dy, cz + dz);
      if (r.end > r.begin) out[rows++] = r;
    }
  return rows;
}

void CellIndex::stencil_cells(std::size_t c, Range* out) const {
  const std::int64_t k = grid_.cells_per_horizon;
  const std::int64_t reach_z = grid_.dims == 3 ? k : 0;
  const auto [cz, cy, cx] = cell_coord_[c];
  for (std::int64_t dz = -reach_z; dz <= reach_z; ++dz)
    for (std::int64_t dy = -k; dy <= k; ++dy) {
      if (grid_.dense) {
        for (std::int64_t dx = -k; dx <= k; ++dx) *out++ = row(cx + dx, cx + dx, cy + dy, cz + dz);
        continue;
      }
      const OccupiedRow& cells = occupied_row(cy + dy, cz + dz);  // looked up once for its 2k+1 cells
      if (cells.first < 0) {  // an empty row: one empty run for every cell of it
        out = std::fill_n(out, 2 * k + 1, Range{0, 0});
        continue;
      }
      std::int64_t begin = column_start(cells, cx - k);
      for (std::int64_t dx = -k; dx <= k; ++dx) {
        const std::int64_t end = column_start(cells, cx + dx + 1);
        *out++ = {begin, end};
        begin = end;
      }
    }
}

int CellIndex::upper_stencil(std::size_t c, Range* out) const {
  const std::int64_t k = grid_.cells_per_horizon;
  const std::int64_t reach_z = grid_.dims == 3 ? k : 0;
  const auto [cz, cy, cx] = cell_coord_[c];
  out[0] = row(cx, cx + k, cy, cz);  // never empty: it starts with cell c
  int rows = 1;
  for (std::int64_t dz = 0; dz <= reach_z; ++dz)
    for (std::int64_t dy = dz == 0 ? 1 : -k; dy <= k; ++dy) {
      const Range r = row(cx - k, cx + k, cy + dy, cz + dz);
      if (r.end > r.begin) out[rows++] = r;
    }
  return rows;
}

}  // namespace horizon
