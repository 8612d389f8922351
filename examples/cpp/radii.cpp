// Per-point radii: every point with its own horizon, combined by a radius rule.
#include <cstdio>
#include <vector>

#include <horizon/generate.hpp>
#include <horizon/radii.hpp>

int main() {
  horizon::PointSet points = horizon::random_cloud(5000, 2, /*seed=*/3);  // 2-D, in [0, 10)^2
  std::vector<double> radii(points.size());
  for (std::size_t i = 0; i < radii.size(); ++i) radii[i] = i % 2 ? 0.2 : 0.6;
  horizon::SearchOptions options;  // options.horizon is not used: the radii are
  // gather: row i holds j when d < r_i (scipy's query_ball_point with an array of radii).
  horizon::NeighborList gather = horizon::search_with_radii(points.view(), radii, horizon::RadiusRule::gather, options);
  // min: d < min(r_i, r_j), symmetric, so a half list is allowed.
  options.half = true;
  horizon::NeighborList pairs = horizon::search_with_radii(points.view(), radii, horizon::RadiusRule::min, options);
  std::printf("gather: %lld entries; min, each pair once: %lld\n", static_cast<long long>(gather.total()),
              static_cast<long long>(pairs.total()));
  return gather.total() > pairs.total() ? 0 : 1;
}
