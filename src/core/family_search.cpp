#include "family_search.hpp"

#include <algorithm>
#include <cstring>

namespace horizon::detail {

namespace {

/// The distance test over every candidate of a cell's stencil, for each point of the cell.
/// Candidates are written unconditionally and kept by advancing the cursor on a hit: no
/// branch to mispredict in the innermost loop.
template <Metric M, int D, bool Half>
void find_families_of(const CellIndex& index, double threshold, CellRun& run,
                      std::int64_t* offsets) {
  const double* x = index.coords(0).data();
  const double* y = index.coords(1).data();
  const double* z = index.coords(2).data();
  const point_id* order = index.order().data();
  std::vector<CellIndex::Range> rows(static_cast<std::size_t>(index.max_stencil_rows()));
  std::vector<point_id>& ids = run.ids;
  std::size_t used = 0;

  for (std::size_t c = run.first_cell; c < run.last_cell; ++c) {
    const int row_count = index.stencil(c, rows.data());
    std::int64_t candidates = 0;
    for (int r = 0; r < row_count; ++r) candidates += rows[r].end - rows[r].begin;
    const auto [first, last] = index.points_of(c);
    for (std::int64_t p = first; p < last; ++p) {
      if (ids.size() < used + static_cast<std::size_t>(candidates))
        ids.resize(std::max(2 * ids.size(), used + static_cast<std::size_t>(candidates)));
      point_id* out = ids.data() + used;
      const point_id self = order[p];
      const double xi = x[p], yi = y[p], zi = z[p];
      std::size_t found = 0;
      for (int r = 0; r < row_count; ++r) {
        for (std::int64_t q = rows[r].begin; q < rows[r].end; ++q) {
          const double d = metric_accumulate<M>(xi - x[q], yi - y[q], D == 3 ? zi - z[q] : 0.0);
          const bool keep = Half ? order[q] > self : q != p;
          out[found] = order[q];
          found += static_cast<std::size_t>((d < threshold) & keep);
        }
      }
      used += found;
      offsets[self + 1] = static_cast<std::int64_t>(found);
    }
  }
  ids.resize(used);
}

template <Metric M, int D>
void dispatch_half(const CellIndex& index, const SearchOptions& options, CellRun& run,
                   std::int64_t* offsets) {
  const double threshold = metric_threshold(M, options.horizon);
  if (options.half)
    find_families_of<M, D, true>(index, threshold, run, offsets);
  else
    find_families_of<M, D, false>(index, threshold, run, offsets);
}

template <Metric M>
void dispatch_dims(const CellIndex& index, const SearchOptions& options, CellRun& run,
                   std::int64_t* offsets) {
  if (index.grid().dims == 3)
    dispatch_half<M, 3>(index, options, run, offsets);
  else
    dispatch_half<M, 2>(index, options, run, offsets);
}

}  // namespace

void find_families(const CellIndex& index, const SearchOptions& options, CellRun& run,
                   std::int64_t* offsets) {
  switch (options.metric) {
    case Metric::euclidean: return dispatch_dims<Metric::euclidean>(index, options, run, offsets);
    case Metric::manhattan: return dispatch_dims<Metric::manhattan>(index, options, run, offsets);
    case Metric::chebyshev: return dispatch_dims<Metric::chebyshev>(index, options, run, offsets);
  }
}

void place_rows(const CellIndex& index, const SearchOptions& options, const CellRun& run,
                const std::int64_t* offsets, point_id* indices) {
  if (run.first_cell == run.last_cell) return;
  const point_id* order = index.order().data();
  const point_id* from = run.ids.data();
  const std::int64_t first = index.points_of(run.first_cell).begin;
  const std::int64_t last = index.points_of(run.last_cell - 1).end;
  for (std::int64_t p = first; p < last; ++p) {
    const point_id i = order[p];
    const auto length = static_cast<std::size_t>(offsets[i + 1] - offsets[i]);
    point_id* to = indices + offsets[i];
    std::memcpy(to, from, length * sizeof(point_id));
    if (options.sort_rows) std::sort(to, to + length);
    from += length;
  }
}

}  // namespace horizon::detail
