#include "sorted_stencil.hpp"

#include <algorithm>
#include <bit>
#include <limits>

namespace horizon::detail {

void SortedStencil::gather(const CellIndex& index, const CellIndex::Range* rows, int row_count) {
  const point_id* order = index.order().data();
  keys_.clear();
  point_id low = std::numeric_limits<point_id>::max(), high = 0;
  for (int r = 0; r < row_count; ++r)
    for (std::int64_t q = rows[r].begin; q < rows[r].end; ++q) {
      low = std::min(low, order[q]);
      high = std::max(high, order[q]);
      keys_.push_back(static_cast<std::uint64_t>(order[q]) << 32 | static_cast<std::uint64_t>(q));
    }
  size_ = static_cast<std::int64_t>(keys_.size());

  // Counting sort by the leading bits of id - low, about one key per bucket, then insertion
  // sort, which moves keys only within their bucket. Scalar merges of the cells' runs were
  // bound by the latency of each comparison (12 us per cell at m = 3.015, this project's Xeon).
  const std::size_t buckets = std::bit_ceil(keys_.size());
  const int shift = std::max(0, static_cast<int>(std::bit_width(static_cast<std::uint32_t>(high - low))) -
                                   std::countr_zero(buckets));
  bucket_start_.assign(buckets + 1, 0);
  for (const std::uint64_t key : keys_) ++bucket_start_[((static_cast<std::uint32_t>(key >> 32) - low) >> shift) + 1];
  for (std::size_t b = 0; b < buckets; ++b) bucket_start_[b + 1] += bucket_start_[b];
  merged_.resize(keys_.size());
  for (const std::uint64_t key : keys_)
    merged_[bucket_start_[(static_cast<std::uint32_t>(key >> 32) - low) >> shift]++] = key;
  insertion_sort(merged_.data(), merged_.data() + merged_.size());
  keys_.swap(merged_);

  const auto padded = keys_.size() + CellIndex::padding;
  for (auto& axis : coords_) axis.resize(padded, std::numeric_limits<double>::quiet_NaN());
  ids_.resize(padded, -1);
  for (std::size_t s = 0; s < keys_.size(); ++s) {
    const auto q = static_cast<std::size_t>(keys_[s] & 0xffffffffu);
    ids_[s] = static_cast<point_id>(keys_[s] >> 32);
    for (int a = 0; a < 3; ++a) coords_[a][s] = index.coords(a)[q];
  }
  for (std::size_t s = keys_.size(); s < padded; ++s) {
    ids_[s] = -1;
    for (auto& axis : coords_) axis[s] = std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace horizon::detail
