#pragma once
/// \file cell_index.hpp
/// Points sorted by the cell they occupy (thesis §4.2.3): the order, the coordinates in that
/// order (structure of arrays, so a stencil row is read contiguously), the occupied cells with
/// their first sorted position, and a lookup from a row of cells to its run of sorted positions.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "horizon/buffer.hpp"
#include "horizon/grid.hpp"
#include "horizon/points.hpp"

namespace horizon {

/// Periodic images sorted into the cells after the points: they hold no row, and families name
/// each image by the point image_of[k] it copies.
struct Images {
  PointView points;
  std::span<const point_id> image_of;
};

class CellIndex {
public:
  /// A run [begin, end) of sorted positions.
  struct Range {
    std::int64_t begin, end;
  };

  /// Vector loads may run past the end of a stencil row: order() and coords() hold this many
  /// entries past point_count() (ids -1, coordinates NaN, so no test ever passes on them).
  static constexpr std::size_t padding = 16;

  /// Sorts `points`, then `images`, into the cells of `grid` on `threads` threads (same result
  /// for any count). Image k takes sorted positions as point point_count() + k, with the id of
  /// the point it copies in order().
  CellIndex(PointView points, const Grid& grid, int threads = 1, Images images = {});

  const Grid& grid() const { return grid_; }
  std::size_t point_count() const { return count_; }
  /// The points that hold rows: all but the images.
  std::size_t row_count() const { return rows_; }
  std::size_t occupied_cells() const { return cell_begin_.empty() ? 0 : cell_begin_.size() - 1; }

  /// Input id of the point at sorted position p.
  const ScratchBuffer<point_id>& order() const { return order_; }
  /// Coordinates along each axis in sorted order (z is all zeros in 2-D).
  const ScratchBuffer<double>& coords(int axis) const { return sorted_[axis]; }
  /// Sorted positions of the points in occupied cell c.
  Range points_of(std::size_t c) const { return {cell_begin_[c], cell_begin_[c + 1]}; }
  /// The first of them, those that hold rows (the cell's images sort after them).
  Range rows_of(std::size_t c) const {
    return {cell_begin_[c], cell_rows_end_.empty() ? cell_begin_[c + 1] : cell_rows_end_[c]};
  }

  /// The stencil of occupied cell c: for each row of cells (cy+dy, cz+dz), |dy|,|dz| <= k, the
  /// run of sorted positions of cells cx-k .. cx+k, which are adjacent in the sort. Empty rows
  /// are skipped; rows come in ascending position order. Returns the number of ranges written.
  int stencil(std::size_t c, Range* out) const;

  /// The part of that stencil in the columns of cells cx + first .. cx + last (-k <= first <=
  /// last <= k), in the same order. Returns the number of ranges written.
  int stencil_columns(std::size_t c, std::int64_t first, std::int64_t last, Range* out) const;

  /// The same stencil cell by cell: the run of each cell (cx+dx, cy+dy, cz+dz), |dx|,|dy|,|dz| <= k,
  /// empty ones included, at out[((dz + kz) * (2k+1) + dy + k) * (2k+1) + dx + k] (kz = k in 3-D,
  /// kz = dz = 0 in 2-D).
  /// A row of cells dx = a .. b is then the run out[.. a].begin .. out[.. b].end. Writes
  /// max_stencil_cells() ranges.
  void stencil_cells(std::size_t c, Range* out) const;

  /// The half of that stencil which comes after cell c in the sort, so that each pair of
  /// points is in the stencil of exactly one of their cells, or both in one cell: first the run
  /// of cells cx .. cx+k (cell c's own points first), then the rows (cy+dy, cz) for dy = 1..k
  /// and (cy+dy, cz+dz) for dz = 1..k. Writes at most max_stencil_rows() ranges.
  int upper_stencil(std::size_t c, Range* out) const;

  /// Coordinate of occupied cell c along the slowest axis of the sort (z in 3-D, y in 2-D): cells
  /// are sorted by it, and an upper stencil reaches layers layer(c) .. layer(c) + k.
  std::int64_t layer(std::size_t c) const { return cell_coord_[c][grid_.dims == 3 ? 0 : 1]; }
  /// Coordinates (cz, cy, cx) of occupied cell c.
  const std::array<std::int64_t, 3>& cell_coord(std::size_t c) const { return cell_coord_[c]; }

  /// Largest number of ranges stencil() can write: (2k+1)^(dims-1).
  int max_stencil_rows() const;
  /// Number of ranges stencil_cells() writes: (2k+1)^dims.
  int max_stencil_cells() const { return max_stencil_rows() * (2 * grid_.cells_per_horizon + 1); }

private:
  /// The run of sorted positions of cells x_first .. x_last of the row of cells (cy, cz). Dense
  /// grids inline: the stencils ask for 5-9 rows a cell.
  Range row(std::int64_t x_first, std::int64_t x_last, std::int64_t cy, std::int64_t cz) const {
    if (!grid_.dense) return sparse_row(x_first, x_last, cy, cz);
    const auto first = static_cast<std::size_t>(grid_.linear_id(x_first, cy, cz));
    const auto last = static_cast<std::size_t>(grid_.linear_id(x_last, cy, cz));
    return {start_by_id_[first], start_by_id_[last + 1]};
  }
  Range sparse_row(std::int64_t x_first, std::int64_t x_last, std::int64_t cy, std::int64_t cz) const;

  /// Sparse grids: an occupied row of cells (cy, cz), its occupied cells [first, end), their
  /// columns low_x .. high_x, and where its column table starts in column_start_ (-1: none).
  struct OccupiedRow {
    std::int64_t cz, cy, first, end, low_x, high_x, table;  ///< first < 0: an empty slot
  };
  /// Fills occupied_rows_, a hash table of the occupied rows (half full at most).
  void index_rows();
  /// Row (cy, cz) of occupied_rows_, or an empty slot.
  const OccupiedRow& occupied_row(std::int64_t cy, std::int64_t cz) const { return occupied_rows_[row_slot(cy, cz)]; }
  /// The slot of occupied_rows_ where row (cy, cz) is, or the empty slot where it would be.
  std::size_t row_slot(std::int64_t cy, std::int64_t cz) const;
  /// The first sorted position at or past column x of an occupied row.
  std::int64_t column_start(const OccupiedRow& row, std::int64_t x) const;

  /// The constructor's work, with coordinate(i, a) giving coordinate a of point i (the points,
  /// then the images).
  template <class Coordinate>
  void build(const Coordinate& coordinate, int threads, Images images);
  template <class Coordinate>
  void sort_dense(const Coordinate& coordinate, int threads);
  template <class Coordinate>
  void sort_sparse(const Coordinate& coordinate, int threads);

  Grid grid_;
  std::size_t count_ = 0, rows_ = 0;
  ScratchBuffer<point_id> order_;
  std::array<ScratchBuffer<double>, 3> sorted_;
  ScratchBuffer<std::int64_t> cell_begin_;  ///< occupied cell -> first sorted position (+ end)
  ScratchBuffer<std::int64_t> cell_rows_end_;  ///< with images: occupied cell -> end of its rows
  ScratchBuffer<std::array<std::int64_t, 3>> cell_coord_;  ///< occupied cell -> (cx, cy, cz)
  ScratchBuffer<std::int64_t> start_by_id_;  ///< dense only: linear cell id -> first position
  ScratchBuffer<OccupiedRow> occupied_rows_;  ///< sparse only: see index_rows()
  /// Sparse only: for each column low_x .. high_x of a row with a table, the first sorted
  /// position at or past it.
  ScratchBuffer<std::int64_t> column_start_;
};

}  // namespace horizon
