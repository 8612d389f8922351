#include "sorted_stencil.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <utility>

namespace horizon::detail {

void SortedStencil::Points::resize(std::size_t count) {
  ids.resize(count);
  for (auto& axis : coords) axis.resize(count);
  column.resize(count);
}

void SortedStencil::Points::pad(std::size_t count) {
  std::fill(ids.begin() + static_cast<std::ptrdiff_t>(count), ids.end(), -1);
  for (auto& axis : coords)
    std::fill(axis.begin() + static_cast<std::ptrdiff_t>(count), axis.end(), std::numeric_limits<double>::quiet_NaN());
}

std::size_t SortedStencil::gather_columns(const CellIndex& index, std::size_t c, std::int64_t first, std::int64_t last,
                                          Points& out, std::size_t at) {
  const point_id* order = index.order().data();
  const std::int64_t cx = index.cell_coord(c)[2];
  CellIndex::Range runs[49];  // (2k + 1)^2 rows of cells at most (k <= 3)
  std::size_t column_end[7];   // where each column's keys end
  keys_.clear();
  positions_.clear();
  point_id low = std::numeric_limits<point_id>::max(), high = 0;
  for (std::int64_t dx = first; dx <= last; ++dx) {
    const int count = index.stencil_columns(c, dx, dx, runs);
    for (int r = 0; r < count; ++r)
      for (std::int64_t q = runs[r].begin; q < runs[r].end; ++q) {
        low = std::min(low, order[q]);
        high = std::max(high, order[q]);
        keys_.push_back(static_cast<std::uint64_t>(order[q]) << 32 | positions_.size());
        positions_.push_back(q);
      }
    column_end[dx - first] = positions_.size();
  }
  const std::size_t size = keys_.size();

  // Counting sort by the leading bits of id - low, about one key per bucket, then insertion
  // sort, which moves keys only within their bucket. Scalar merges of the cells' runs were
  // bound by the latency of each comparison (12 us per cell at m = 3.015, this project's Xeon).
  const std::size_t buckets = std::bit_ceil(size);
  const int shift = std::max(0, static_cast<int>(std::bit_width(static_cast<std::uint32_t>(high - low))) -
                                   std::countr_zero(buckets));
  bucket_start_.assign(buckets + 1, 0);
  for (const std::uint64_t key : keys_) ++bucket_start_[((static_cast<std::uint32_t>(key >> 32) - low) >> shift) + 1];
  for (std::size_t b = 0; b < buckets; ++b) bucket_start_[b + 1] += bucket_start_[b];
  merged_.resize(size);
  for (const std::uint64_t key : keys_)
    merged_[bucket_start_[(static_cast<std::uint32_t>(key >> 32) - low) >> shift]++] = key;
  insertion_sort(merged_.data(), merged_.data() + size);

  out.resize(at + size + CellIndex::padding);
  for (std::size_t s = 0; s < size; ++s) {
    const std::size_t from = merged_[s] & 0xffffffffu;
    const auto q = static_cast<std::size_t>(positions_[from]);
    out.ids[at + s] = static_cast<point_id>(merged_[s] >> 32);
    for (int a = 0; a < 3; ++a) out.coords[a][at + s] = index.coords(a)[q];
    std::int64_t column = cx + first;
    for (std::int64_t d = 0; d < last - first; ++d) column += from >= column_end[d];
    out.column[at + s] = column;
  }
  return size;
}

void SortedStencil::gather(const CellIndex& index, std::size_t c) {
  const auto& cell = index.cell_coord(c);
  const std::int64_t k = index.grid().cells_per_horizon;
  if (!(cell[0] == cell_[0] && cell[1] == cell_[1] && cell[2] == cell_[2] + 1)) {
    size_ = gather_columns(index, c, -k, k, stencil_, 0);
  } else {
    // Entry s of `from` becomes entry o of `to`.
    const auto copy = [](const Points& from, std::size_t s, Points& to, std::size_t o) {
      to.ids[o] = from.ids[s];
      for (int axis = 0; axis < 3; ++axis) to.coords[axis][o] = from.coords[axis][s];
      to.column[o] = from.column[s];
    };
    // The last stencil less its first column, in place, then its new last column after it, and
    // the two runs merged.
    const std::int64_t dropped = cell[2] - k - 1;
    Points& a = stencil_;
    std::size_t kept = 0;
    for (std::size_t s = 0; s < size_; ++s) {
      copy(a, s, a, kept);
      kept += a.column[s] != dropped;
    }
    const std::size_t end = kept + gather_columns(index, c, k, k, a, kept);
    Points& out = merged_points_;
    out.resize(end + CellIndex::padding);
    std::size_t i = 0, j = kept, o = 0;
    for (; i < kept && j < end; ++o) {
      // Which run's entry comes next is unpredictable for ids in random order: chosen by
      // arithmetic, as GCC branches on a conditional here (10 % of a search of random points).
      const std::size_t from_a = a.ids[i] < a.ids[j];
      copy(a, j ^ ((i ^ j) & (0 - from_a)), out, o);
      i += from_a;
      j += 1 - from_a;
    }
    for (; i < kept; ++i, ++o) copy(a, i, out, o);
    for (; j < end; ++j, ++o) copy(a, j, out, o);
    std::swap(stencil_, merged_points_);
    size_ = o;
  }
  stencil_.pad(size_);
  cell_ = cell;
}

}  // namespace horizon::detail
