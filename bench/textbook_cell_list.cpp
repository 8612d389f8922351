#include "textbook_cell_list.hpp"

#include <algorithm>
#include <cmath>

#include "horizon/stopwatch.hpp"

namespace bench {

TextbookList textbook_cell_list(const horizon::PointSet& points, double horizon, int threads) {
  TextbookList list;
  horizon::Stopwatch clock;
  const auto n = static_cast<std::int64_t>(points.size());
  const double* xyz = points.xyz.data();

  // Grid: cells of side `horizon` over the bounding box, one empty cell of padding each side.
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = n ? xyz[a] : 0;
  for (std::int64_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], xyz[3 * i + a]);
      hi[a] = std::max(hi[a], xyz[3 * i + a]);
    }
  std::int64_t dim[3];
  for (int a = 0; a < 3; ++a) dim[a] = static_cast<std::int64_t>((hi[a] - lo[a]) / horizon) + 3;
  const std::int64_t cells = dim[0] * dim[1] * dim[2];
  std::vector<std::int64_t> cell(n), start(cells + 1, 0);
  for (std::int64_t i = 0; i < n; ++i) {
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a) c[a] = static_cast<std::int64_t>((xyz[3 * i + a] - lo[a]) / horizon) + 1;
    cell[i] = c[0] + dim[0] * (c[1] + dim[1] * c[2]);
    ++start[cell[i] + 1];
  }
  for (std::int64_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<std::int64_t> next(start.begin(), start.end() - 1);
  std::vector<std::int32_t> id(n);
  std::vector<double> x(n), y(n), z(n);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t p = next[cell[i]]++;
    id[p] = static_cast<std::int32_t>(i);
    x[p] = xyz[3 * i];
    y[p] = xyz[3 * i + 1];
    z[p] = xyz[3 * i + 2];
  }
  list.grid_seconds = clock.lap();

  // One pass over the cells, counting (Fill = false) or writing (Fill = true) each family.
  const double r2 = horizon * horizon;
  list.offsets.assign(n + 1, 0);
  std::int64_t candidates = 0;
  auto pass = [&]<bool Fill>() {
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads) reduction(+ : candidates)
    for (std::int64_t c = 0; c < cells; ++c) {
      if (start[c] == start[c + 1]) continue;
      for (std::int64_t p = start[c]; p < start[c + 1]; ++p) {
        std::int64_t found = 0;
        std::int32_t* out = Fill ? list.indices.data() + list.offsets[id[p]] : nullptr;
        for (std::int64_t dz = -1; dz <= 1; ++dz)
          for (std::int64_t dy = -1; dy <= 1; ++dy) {
            const std::int64_t row = c + dim[0] * (dy + dim[1] * dz);
            const std::int64_t first = start[row - 1], last = start[row + 2];
            if (!Fill) candidates += last - first;
            for (std::int64_t q = first; q < last; ++q) {
              const double ddx = x[p] - x[q], ddy = y[p] - y[q], ddz = z[p] - z[q];
              const bool hit = (ddx * ddx + ddy * ddy) + ddz * ddz < r2 && q != p;
              if constexpr (Fill) {
                if (hit) *out++ = id[q];
              } else {
                found += hit;
              }
            }
          }
        if (!Fill) list.offsets[id[p] + 1] = found;
      }
    }
  };
  pass.operator()<false>();
  for (std::int64_t i = 0; i < n; ++i) list.offsets[i + 1] += list.offsets[i];
  list.indices.resize(static_cast<std::size_t>(list.offsets[n]));  // not zeroed: Buffer
  pass.operator()<true>();
  list.search_seconds = clock.lap();
  list.candidates_per_point = n ? static_cast<double>(candidates) / static_cast<double>(n) : 0;
  return list;
}

}  // namespace bench
