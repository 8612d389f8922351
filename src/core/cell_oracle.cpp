// The cell search's oracle: every pair of points, every shift within reach of their fractional
// difference (no wrapping, no images, no grid), tested and written as the search does.
#include <cmath>
#include <vector>

#include "cell_problem.hpp"
#include "cell_search.hpp"

namespace horizon::detail {
namespace {

template <int D, Metric M>
NeighborList oracle(PointView points, const CellProblem& problem) {
  const std::size_t n = points.size();
  std::vector<double> x(n * D), f(n * 3, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < D; ++a) x[i * D + a] = points(i, a);
    for (int a = 0; a < D; ++a)
      if (problem.frame.pbc[a]) f[i * 3 + a] = problem.frame.fractional(&x[i * D], a);
  }
  std::vector<CellEntry> kept;
  Buffer<std::int64_t> offsets{0};
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
      for (int a = 0; a < D; ++a)
        if (problem.frame.pbc[a]) {
          // |f_j + S - f_i| <= reach, one more on each side for rounding.
          const double reach = problem.cells_reach(a), difference = f[j * 3 + a] - f[i * 3 + a];
          lo[a] = static_cast<std::int64_t>(std::ceil(-reach - difference)) - 1;
          hi[a] = static_cast<std::int64_t>(std::floor(reach - difference)) + 1;
        }
      for (std::int64_t s0 = lo[0]; s0 <= hi[0]; ++s0)
        for (std::int64_t s1 = lo[1]; s1 <= hi[1]; ++s1)
          for (std::int64_t s2 = lo[2]; s2 <= hi[2]; ++s2) {
            CellEntry e;
            e.j = static_cast<point_id>(j);
            e.shift[0] = static_cast<std::int32_t>(s0);
            e.shift[1] = static_cast<std::int32_t>(s1);
            e.shift[2] = static_cast<std::int32_t>(s2);
            measure<D, M>(&x[i * D], &x[j * D], problem.frame, e);
            if (e.accumulated < problem.threshold(i, j) && problem.keeps(static_cast<point_id>(i), e)) kept.push_back(e);
          }
    }
    offsets.push_back(static_cast<std::int64_t>(kept.size()));
  }
  CellEntries entries(kept.size(), D, problem.outputs, problem.metric);
  for (std::size_t e = 0; e < kept.size(); ++e) entries.write(e, kept[e]);
  return std::move(entries).list(std::move(offsets), problem.half);
}

}  // namespace

NeighborList brute_force_cell(PointView points, const SearchOptions& options, std::span<const double> radii,
                              RadiusRule rule) {
  const CellProblem problem = cell_problem(points, options, radii, rule);
  return with_dims_and_metric(points.dims(), problem.metric,
                              [&](auto d, auto m) { return oracle<decltype(d)::value, decltype(m)::value>(points, problem); });
}

}  // namespace horizon::detail
