#pragma once
// The points of one cell's stencil gathered into one array in ascending id order (structure of
// arrays). Every family of the cell's points, found by scanning this array in order, comes out
// sorted: no row is ever sorted. The cost is one sort per cell, shared by all its points, and
// less when the cells come in order along x: the next cell's stencil is this one less its first
// column of cells, merged with its new last column (a third of the points to sort, for k = 1).
#include <array>
#include <cstdint>
#include <vector>

#include "horizon/cell_index.hpp"

namespace horizon::detail {

/// Sorts [first, last) ascending by insertion: fastest for a few keys, or keys nearly in order.
template <class T>
void insertion_sort(T* first, T* last) {
  for (T* i = first + 1; i < last; ++i) {
    const T value = *i;
    T* j = i;
    for (; j > first && j[-1] > value; --j) *j = j[-1];
    *j = value;
  }
}

class SortedStencil {
public:
  /// Gathers the points of occupied cell c's stencil (CellIndex::stencil): from the last one
  /// gathered when that was the cell before c along x, else afresh.
  void gather(const CellIndex& index, std::size_t c);

  /// Number of points; the arrays hold CellIndex::padding more (NaN coordinates, id -1).
  std::int64_t size() const { return static_cast<std::int64_t>(size_); }
  const double* coords(int axis) const { return stencil_.coords[axis].data(); }
  const point_id* ids() const { return stencil_.ids.data(); }

private:
  /// The points of one stencil (or of the column added to it): ids ascending, coordinates, and
  /// the x coordinate of each point's cell; padded like the cell index.
  struct Points {
    std::vector<point_id> ids;
    std::vector<double> coords[3];
    std::vector<std::int64_t> column;
    void resize(std::size_t count);
    /// Marks every entry from `count` on as no point (id -1, NaN coordinates).
    void pad(std::size_t count);
  };

  /// Columns cx + first .. cx + last of cell c's stencil into `out` from entry `at` on, sorted
  /// by id; returns their number of points.
  std::size_t gather_columns(const CellIndex& index, std::size_t c, std::int64_t first, std::int64_t last, Points& out,
                             std::size_t at);

  std::vector<std::uint64_t> keys_, merged_;  ///< id << 32 | index into positions_
  std::vector<std::int64_t> positions_;       ///< sorted positions, column after column
  std::vector<std::uint32_t> bucket_start_;
  Points stencil_, merged_points_;
  std::size_t size_ = 0;
  /// (cz, cy, cx) of the stencil gathered last; cell coordinates are >= 0, so none at first.
  std::array<std::int64_t, 3> cell_{-1, -1, -1};
};

}  // namespace horizon::detail
