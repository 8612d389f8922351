// The Verlet list: refresh() equals a fresh search while no point has moved skin / 2, for
// every metric, full and half lists, 2-D and 3-D; needs_rebuild() turns true past that.
#include <gtest/gtest.h>

#include <random>

#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/verlet_list.hpp"

namespace horizon {
namespace {

// Every point moved by a random step of `size` (in the metric: Chebyshev per axis, the others
// bounded by the Euclidean length, which bounds them from above in l2 and needs /dims in l1).
PointSet moved(const PointSet& points, double size, Metric metric, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  PointSet out = points;
  const double per_axis = metric == Metric::chebyshev ? size : size / points.dims;
  for (double& x : out.xyz) x += per_axis * unit(rng);
  return out;
}

TEST(VerletList, RefreshEqualsAFreshSearchWithinHalfTheSkin) {
  std::mt19937_64 rng(3);
  for (int dims : {2, 3})
    for (Metric metric : {Metric::euclidean, Metric::manhattan, Metric::chebyshev})
      for (bool half : {false, true}) {
        const PointSet points = clustered_cloud(4000, 6, 0.8, dims, 4);
        SearchOptions options;
        options.horizon = dims == 3 ? 0.6 : 0.25;
        options.metric = metric;
        options.half = half;
        const double skin = 0.2 * options.horizon;
        const VerletList verlet(points.view(), options, skin);
        for (double step : {0.0, 0.2 * skin, 0.49 * skin}) {
          const PointSet now = moved(points, step, metric, rng);
          ASSERT_FALSE(verlet.needs_rebuild(now.view())) << step;
          EXPECT_EQ(verlet.refresh(now.view()), search(now.view(), options))
              << dims << "-D " << metric_name(metric) << (half ? " half" : " full") << " step " << step;
          EXPECT_EQ(verlet.refresh(now.view(), 1), verlet.refresh(now.view()));
        }
        PointSet far = points;
        far.xyz[0] += 0.5 * skin;  // one point moved half the skin along x
        EXPECT_TRUE(verlet.needs_rebuild(far.view()));
      }
}

// Millions of candidates (a lattice and a dense blob of rows of 2,000 and more) refreshed on
// one thread and on more threads than this machine has cores give the fresh search's list.
TEST(VerletList, RefreshOfALargeListOnAnyThreadCount) {
  PointSet points = lattice(30, 3, 10.0);
  const PointSet blob = random_cloud(2000, 3, 5, 0.05);
  for (std::size_t i = 0; i < blob.xyz.size(); ++i) points.xyz.push_back(blob.xyz[i] + 4.02);
  SearchOptions options;
  options.horizon = 3.015 * 10.0 / 29;
  const VerletList verlet(points.view(), options, 0.1 * options.horizon);
  std::mt19937_64 rng(9);
  const PointSet now = moved(points, 0.02 * options.horizon, Metric::euclidean, rng);
  ASSERT_FALSE(verlet.needs_rebuild(now.view()));
  const NeighborList fresh = search(now.view(), options);
  ASSERT_GT(fresh.total(), std::int64_t{2000} * 2000);
  for (int threads : {1, 3, 8}) EXPECT_EQ(verlet.refresh(now.view(), threads), fresh) << threads << " threads";
}

TEST(VerletList, ClearErrors) {
  const PointSet points = random_cloud(100, 3, 1);
  SearchOptions options;
  options.horizon = 1;
  EXPECT_THROW(VerletList(points.view(), options, 0), Error);
  const VerletList verlet(points.view(), options, 0.1);
  const PointSet fewer = random_cloud(99, 3, 1);
  EXPECT_THROW(verlet.refresh(fewer.view()), Error);
  options.box = {10, 10, 10};
  EXPECT_THROW(VerletList(points.view(), options, 0.1), Error);
}

}  // namespace
}  // namespace horizon
