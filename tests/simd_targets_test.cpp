// The CPU passes are compiled for several instruction sets and dispatched at run time: every one
// this machine can run (AVX-512, AVX2, SSE4, ... down to the emulated fallback) must give the
// oracle's list, for every metric, dimension, cell size, list kind and row order.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <tuple>

#include "bond_filter_oracle.hpp"
#include "datasets.hpp"
#include "horizon/bond_filter.hpp"
#include "horizon/generate.hpp"
#include "horizon/oracle.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"
#include "horizon/verlet_list.hpp"

namespace horizon::testing {
namespace {

/// Runs `test(target)` with each SIMD target this CPU runs and this build compiled forced;
/// returns how many ran.
template <class Test>
int for_each_target(Test test) {
  const std::int64_t supported = hwy::SupportedTargets();
  int targets_run = 0;
  for (const std::int64_t target : {HWY_AVX3_DL, HWY_AVX3, HWY_AVX2, HWY_SSE4, HWY_SSSE3, HWY_EMU128}) {
    if (!(supported & target)) continue;
    hwy::SetSupportedTargetsForTest(target);
    if (std::string(cpu_simd_target()) != hwy::TargetName(target)) continue;  // not compiled in
    ++targets_run;
    test(target);
  }
  hwy::SetSupportedTargetsForTest(0);
  return targets_run;
}

TEST(SimdTargets, EveryTargetThisCpuRunsMatchesBruteForce) {
  // The oracle's list depends on neither the target, k nor the row order: computed once each.
  std::map<std::tuple<int, std::string, Metric, bool>, NeighborList> oracle;
  const int targets_run = for_each_target([&](std::int64_t target) {
    for (int dims : {2, 3})
      for (const Dataset& data : datasets(dims))
        for (Metric metric : {Metric::euclidean, Metric::manhattan, Metric::chebyshev})
          for (int k : {1, 2})
            for (bool half : {false, true})
              for (bool sorted : {true, false}) {
                SearchOptions options = options_for(data, metric, k, half);
                options.sort_rows = sorted;
                NeighborList list = search(data.points.view(), options);
                auto [at, fresh] = oracle.try_emplace(std::tuple{dims, data.name, metric, half});
                if (fresh) at->second = brute_force(data.points.view(), options);
                const NeighborList& expected = at->second;
                const std::string where = std::string(hwy::TargetName(target)) + " " + data.name + " " +
                                          metric_name(metric) + " k" + std::to_string(k) + (half ? " half" : "") +
                                          (sorted ? "" : " unsorted");
                ASSERT_EQ(list.offsets(), expected.offsets()) << where;
                if (sorted) {
                  EXPECT_EQ(list.indices(), expected.indices()) << where;
                } else {
                  for (std::size_t i = 0; i < list.size(); ++i) {
                    std::vector<point_id> row(list.row(i).begin(), list.row(i).end());
                    std::sort(row.begin(), row.end());
                    ASSERT_TRUE(std::equal(row.begin(), row.end(), expected.row(i).begin())) << where << " row " << i;
                  }
                }
              }
  });
#if defined(HORIZON_NATIVE_BUILD)
  EXPECT_GE(targets_run, 1);  // -march=native compiles only this CPU's best target
#else
  EXPECT_GE(targets_run, 2) << "a portable build dispatches to this CPU's best target and fallbacks";
#endif
}

// The Verlet refresh tests its stored candidates with its own kernel (four or two candidates
// per step and a scalar tail, bits in 64-entry words): on every target it must give the oracle's
// list, ties on the horizon and rows longer than 64 candidates included.
TEST(SimdTargets, VerletRefreshMatchesBruteForceOnEveryTarget) {
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims))
      for (Metric metric : {Metric::euclidean, Metric::manhattan, Metric::chebyshev})
        for (bool half : {false, true}) {
          const SearchOptions options = options_for(data, metric, 1, half);
          const NeighborList expected = brute_force(data.points.view(), options);
          for_each_target([&](std::int64_t target) {
            const VerletList verlet(data.points.view(), options, 0.3 * data.horizon);
            EXPECT_EQ(verlet.refresh(data.points.view(), 1), expected)
                << hwy::TargetName(target) << " " << data.name << " " << metric_name(metric) << (half ? " half" : "");
          });
        }
}

// Bond filters test a row's bonds in lanes, from masks gathered by id (and `cuts` for the bonds
// the masks leave open): random shapes over clouds (rows of every length, tails of every size)
// and shapes through lattice points, on every target.
TEST(SimdTargets, BondFiltersMatchBruteForceOnEveryTarget) {
  std::mt19937_64 rng(11);
  struct Scene {
    std::string name;
    PointSet points;
    std::vector<BondFilter> filters;
    double horizon;
  };
  std::vector<Scene> scenes;
  for (int dims : {2, 3})
    scenes.push_back({"cloud " + std::to_string(dims) + "-D", random_cloud(3000, dims, 5), random_filters(rng, 20, dims),
                      dims == 3 ? 1.0 : 0.4});
  for (double offset : {0.0, 1e6}) {
    auto [points, filters] = shapes_on_lattice(offset);
    scenes.push_back({"lattice at " + std::to_string(offset), std::move(points), std::move(filters), 1.8});
  }
  for (const Scene& scene : scenes)
    for (bool half : {false, true}) {
      SearchOptions options;
      options.horizon = scene.horizon;
      options.half = half;
      const NeighborList list = search(scene.points.view(), options);
      const NeighborList expected = brute_force_filter(list, scene.points, scene.filters);
      for_each_target([&](std::int64_t target) {
        EXPECT_EQ(filter_bonds(list, scene.points.view(), scene.filters, options.horizon), expected)
            << hwy::TargetName(target) << " " << scene.name << (half ? " half" : "");
      });
    }
}

// Rows of every length from 0 to 140 ids, arriving in random id order: every size of the
// in-register sorting network (1, 2, 4 and 8 vectors: up to 128 ids with AVX-512), its padding,
// and the longer rows sorted otherwise. Group g is g + 1 points at one spot, far from the others.
TEST(SimdTargets, RowsOfEveryLengthAreSortedOnEveryTarget) {
  std::vector<double> xyz;
  for (int group = 0; group <= 140; ++group)
    for (int member = 0; member <= group; ++member) xyz.insert(xyz.end(), {10.0 * group, 0.5 * (group % 3), 0.0});
  const std::size_t n = xyz.size() / 3;
  std::vector<std::size_t> shuffled(n);
  std::iota(shuffled.begin(), shuffled.end(), std::size_t{0});
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(7));
  std::vector<double> points(xyz.size());
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) points[3 * shuffled[i] + a] = xyz[3 * i + a];
  const PointView view(points.data(), n, 3);
  SearchOptions options;
  options.horizon = 1.0;
  const NeighborList full = brute_force(view, options);
  options.half = true;
  const NeighborList upper = brute_force(view, options);
  for_each_target([&](std::int64_t target) {
    for (Backend backend : {Backend::serial, Backend::openmp})
      for (bool half : {false, true}) {
        options.backend = backend;
        options.half = half;
        const NeighborList list = search(view, options);
        const NeighborList& expected = half ? upper : full;
        EXPECT_EQ(list.offsets(), expected.offsets()) << hwy::TargetName(target);
        EXPECT_EQ(list.indices(), expected.indices()) << hwy::TargetName(target) << (half ? " half" : "");
      }
  });
}

// Large stencils (256 candidates or more) whose rows are sorted either by the network, when every
// row of the cell fits it, or from the cell's sorted stencil, when one does not: a cloud whose
// density grows along x, so rows grow from ~60 to ~250 ids and cells of both kinds alternate
// (which also breaks and resumes the sorted stencil's slide along x).
TEST(SimdTargets, LargeStencilsGiveSortedRowsWhateverTheirRowsLengths) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> xyz;
  while (xyz.size() < 3 * 7000) {
    const double x = 20.0 * unit(rng), y = 3.0 * unit(rng), z = 3.0 * unit(rng);
    if (unit(rng) < (14.0 + 46.0 * x / 20.0) / 60.0) xyz.insert(xyz.end(), {x, y, z});
  }
  const PointView view(xyz.data(), xyz.size() / 3, 3);
  SearchOptions options;
  options.horizon = 1.0;
  const NeighborList expected = brute_force(view, options);
  std::size_t short_rows = 0, long_rows = 0;  // well within, and well beyond, AVX-512's network (128)
  for (std::size_t i = 0; i < expected.size(); ++i) {
    short_rows += expected.row_size(i) <= 100;
    long_rows += expected.row_size(i) > 140;
  }
  ASSERT_GT(short_rows, 500u);
  ASSERT_GT(long_rows, 500u);
  options.half = true;
  const NeighborList upper = brute_force(view, options);
  for_each_target([&](std::int64_t target) {
    for (Backend backend : {Backend::serial, Backend::openmp})
      for (bool half : {false, true}) {
        options.backend = backend;
        options.half = half;
        const NeighborList list = search(view, options);
        EXPECT_EQ(list, half ? upper : expected) << hwy::TargetName(target) << (half ? " half" : "");
      }
  });
}

// Per-point radii: each row tests only the cells its radius reaches, and a row longer than the
// sorting network takes the cell's sorted stencil (gather) or is sorted otherwise (min). Dense clouds (rows up to ~1500 ids, stencils
// of thousands) and a lattice whose points lie on cell faces and at distances equal to radii,
// k = 1-3, on every target.
TEST(SimdTargets, RadiiRowsFromTheCellsTheyReachMatchBruteForce) {
  struct Cloud {
    std::string name;
    PointSet points;
    double horizon;
  };
  std::vector<Cloud> clouds;
  for (int dims : {2, 3}) {
    clouds.push_back({"dense " + std::to_string(dims) + "-D", random_cloud(dims == 3 ? 3000 : 2000, dims, 5, 3.0), 0.5});
    clouds.push_back({"lattice " + std::to_string(dims) + "-D", lattice(dims == 3 ? 12 : 40, dims, dims == 3 ? 12 : 40), 1.5});
  }
  for (Cloud& cloud : clouds) {
    std::vector<double> radii(cloud.points.size());
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> exponent(std::log(0.3), std::log(3.0));
    const bool on_lattice = cloud.name.starts_with("lattice");
    const double lattice_radii[] = {0.5, 1.0, 2.0, 3.0, 4.0};  // distances on the lattice: ties
    for (double& r : radii) r = on_lattice ? lattice_radii[rng() % 5] : cloud.horizon * std::exp(exponent(rng));
    for (Metric metric : {Metric::euclidean, Metric::manhattan, Metric::chebyshev})
      for (RadiusRule rule : {RadiusRule::gather, RadiusRule::min}) {  // min: each candidate's radius too
        SearchOptions options;
        options.metric = metric;
        const NeighborList expected = brute_force_with_radii(cloud.points.view(), radii, rule, options);
        for_each_target([&](std::int64_t target) {
          for (int k : {1, 2, 3}) {
            options.cells_per_horizon = k;
            const NeighborList list = search_with_radii(cloud.points.view(), radii, rule, options);
            const std::string where = std::string(hwy::TargetName(target)) + " " + cloud.name + " " +
                                      metric_name(metric) + " " + radius_rule_name(rule) + " k" + std::to_string(k);
            ASSERT_EQ(list.offsets(), expected.offsets()) << where;
            EXPECT_EQ(list.indices(), expected.indices()) << where;
          }
        });
      }
  }
}

}  // namespace
}  // namespace horizon::testing
