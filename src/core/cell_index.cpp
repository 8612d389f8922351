#include "horizon/cell_index.hpp"

#include <algorithm>

namespace horizon {

namespace {

std::array<std::int64_t, 3> cell_of_point(PointView points, const Grid& grid, std::size_t i) {
  std::array<std::int64_t, 3> c{0, 0, 0};
  for (int a = 0; a < grid.dims; ++a) c[a] = grid.cell_of(points(i, a), a);
  return c;
}

}  // namespace

CellIndex::CellIndex(PointView points, const Grid& grid) : grid_(grid) {
  const std::size_t n = points.size();
  order_.resize(n);
  if (grid_.dense) {
    // Counting sort by linear cell id (thesis §4.2.3): count, exclusive scan, place. Stable,
    // so a cell's points keep their input order.
    const auto cells = static_cast<std::size_t>(grid_.cell_count());
    start_by_id_.assign(cells + 1, 0);
    std::vector<std::int64_t> id(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = cell_of_point(points, grid_, i);
      id[i] = grid_.linear_id(c[0], c[1], c[2]);
      ++start_by_id_[static_cast<std::size_t>(id[i]) + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) start_by_id_[c + 1] += start_by_id_[c];
    std::vector<std::int64_t> next(start_by_id_.begin(), start_by_id_.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      order_[static_cast<std::size_t>(next[static_cast<std::size_t>(id[i])]++)] =
          static_cast<point_id>(i);
    // Occupied cells: the non-empty entries of the table, x fastest, as in the sort.
    for (std::size_t c = 0; c < cells; ++c) {
      if (start_by_id_[c + 1] == start_by_id_[c]) continue;
      const auto linear = static_cast<std::int64_t>(c);
      cell_coord_.push_back({linear / (grid_.cells[0] * grid_.cells[1]),
                             linear / grid_.cells[0] % grid_.cells[1], linear % grid_.cells[0]});
      cell_begin_.push_back(start_by_id_[c]);
    }
  } else {
    // Sparse: sort (cz, cy, cx, id) tuples; memory stays O(N) whatever the extent.
    std::vector<std::array<std::int64_t, 4>> keys(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = cell_of_point(points, grid_, i);
      keys[i] = {c[2], c[1], c[0], static_cast<std::int64_t>(i)};
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t p = 0; p < n; ++p) {
      order_[p] = static_cast<point_id>(keys[p][3]);
      const std::array<std::int64_t, 3> cell{keys[p][0], keys[p][1], keys[p][2]};
      if (p == 0 || cell != cell_coord_.back()) {
        cell_coord_.push_back(cell);
        cell_begin_.push_back(static_cast<std::int64_t>(p));
      }
    }
  }
  cell_begin_.push_back(static_cast<std::int64_t>(n));

  for (int a = 0; a < 3; ++a) sorted_[a].resize(n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (int a = 0; a < grid_.dims; ++a) sorted_[a][p] = points(order_[p], a);
}

int CellIndex::max_stencil_rows() const {
  const int width = 2 * grid_.cells_per_horizon + 1;
  return grid_.dims == 3 ? width * width : width;
}

CellIndex::Range CellIndex::row_dense(std::int64_t cx, std::int64_t cy, std::int64_t cz) const {
  const std::int64_t k = grid_.cells_per_horizon;
  const auto first = static_cast<std::size_t>(grid_.linear_id(cx - k, cy, cz));
  const auto last = static_cast<std::size_t>(grid_.linear_id(cx + k, cy, cz));
  return {start_by_id_[first], start_by_id_[last + 1]};
}

CellIndex::Range CellIndex::row_sparse(std::int64_t cx, std::int64_t cy, std::int64_t cz) const {
  const std::int64_t k = grid_.cells_per_horizon;
  const auto first = std::lower_bound(cell_coord_.begin(), cell_coord_.end(),
                                      std::array<std::int64_t, 3>{cz, cy, cx - k});
  const auto last = std::lower_bound(first, cell_coord_.end(),
                                     std::array<std::int64_t, 3>{cz, cy, cx + k + 1});
  return {cell_begin_[static_cast<std::size_t>(first - cell_coord_.begin())],
          cell_begin_[static_cast<std::size_t>(last - cell_coord_.begin())]};
}

int CellIndex::stencil(std::size_t c, Range* out) const {
  const std::int64_t k = grid_.cells_per_horizon;
  const std::int64_t reach_z = grid_.dims == 3 ? k : 0;
  const auto [cz, cy, cx] = cell_coord_[c];
  int rows = 0;
  for (std::int64_t dz = -reach_z; dz <= reach_z; ++dz)
    for (std::int64_t dy = -k; dy <= k; ++dy) {
      const Range r = grid_.dense ? row_dense(cx, cy + dy, cz + dz) : row_sparse(cx, cy + dy, cz + dz);
      if (r.end > r.begin) out[rows++] = r;
    }
  return rows;
}

}  // namespace horizon
