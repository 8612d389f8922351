#pragma once
// The points of one cell's stencil gathered into one array in ascending id order (structure of
// arrays). Every family of the cell's points, found by scanning this array in order, comes out
// sorted: no row is ever sorted. The cost is one sort per cell, shared by all its points.
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
  /// Gathers the points of `rows` (a cell's stencil from CellIndex::stencil).
  void gather(const CellIndex& index, const CellIndex::Range* rows, int row_count);

  /// Number of points; the arrays hold CellIndex::padding more (NaN coordinates, id -1).
  std::int64_t size() const { return size_; }
  const double* coords(int axis) const { return coords_[axis].data(); }
  const point_id* ids() const { return ids_.data(); }

private:
  std::int64_t size_ = 0;
  std::vector<std::uint64_t> keys_, merged_;  ///< id << 32 | sorted position
  std::vector<std::uint32_t> bucket_start_;
  std::vector<double> coords_[3];
  std::vector<point_id> ids_;
};

}  // namespace horizon::detail
