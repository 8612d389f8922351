// Properties of search() beyond oracle equality: closed-form lattice counts at sizes brute force
// cannot reach, backend agreement, float32 input, options, and errors.
#include <gtest/gtest.h>
#include <sched.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "core/family_search.hpp"
#include "datasets.hpp"
#include "same_families.hpp"
#include "horizon/cell_index.hpp"
#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/grid.hpp"
#include "horizon/oracle.hpp"
#include "horizon/search.hpp"

namespace horizon {
namespace {

SearchOptions options_for(double horizon, Backend backend = Backend::serial, int k = 1) {
  SearchOptions options;
  options.horizon = horizon;
  options.backend = backend;
  options.cells_per_horizon = k;
  return options;
}

TEST(LatticeCounts, MatchClosedForm) {
  for (int dims : {2, 3})
    for (double m : {1.5, 3.015})
      for (Metric metric : {Metric::euclidean, Metric::manhattan, Metric::chebyshev})
        for (int k : {1, 2, 3}) {
          const int n = dims == 3 ? 24 : 150;
          const PointSet points = lattice(n, dims);
          SearchOptions options = options_for(m * 10.0 / n, Backend::openmp, k);
          options.metric = metric;
          EXPECT_EQ(search(points.view(), options).total(), lattice_entries(n, dims, m, metric))
              << dims << "-D m=" << m << " " << metric_name(metric) << " k=" << k;
        }
}

TEST(LatticeCounts, ThesisNeighbourCounts) {
  // Interior points have 18 neighbours at m = 1.5 and 122 at m = 3.015 (DESIGN.md).
  const PointSet points = lattice(9);
  const std::size_t centre = 4 + 9 * (4 + 9 * 4);
  EXPECT_EQ(search(points.view(), options_for(1.5 * 10.0 / 9)).row_size(centre), 18u);
  EXPECT_EQ(search(points.view(), options_for(3.015 * 10.0 / 9)).row_size(centre), 122u);
}

TEST(Backends, OpenmpEqualsSerialOnLargerClouds) {
  for (const PointSet& points : {random_cloud(60000, 3, 1), clustered_cloud(60000, 20, 0.2, 3, 2),
                                 random_cloud(60000, 2, 3)}) {
    SearchOptions serial = options_for(points.dims == 3 ? 0.4 : 0.06);
    SearchOptions openmp = serial;
    openmp.backend = Backend::openmp;
    openmp.threads = 3;
    EXPECT_EQ(search(points.view(), serial), search(points.view(), openmp));
  }
}

// The count pass tests each pair once, over slabs of cell layers two threads never share (one
// parity at a time): slabs of a few points each at 16 threads, every dataset, k = 1 and 2.
TEST(Backends, CountingEachPairOnceMatchesBruteForceOnAnyThreadCount) {
  for (const int dims : {2, 3})
    for (const auto& data : testing::datasets(dims))
      for (const bool half : {false, true}) {
        const NeighborList expected = brute_force(data.points.view(), testing::options_for(data, Metric::euclidean, 1, half));
        for (const int k : {1, 2})
          for (const int threads : {1, 2, 7, 16}) {
            SearchOptions options = testing::options_for(data, Metric::euclidean, k, half, Backend::openmp);
            options.threads = threads;
            EXPECT_EQ(search(data.points.view(), options), expected)
                << data.name << " " << dims << "-D half " << half << " k " << k << " threads " << threads;
          }
      }
}

// The count pass's blocks of one colour run at once: each occupied cell is in one block, and
// no two blocks of a colour reach the same cell (layers z .. z + k, lines y - k .. y + k of
// their cells: the upper stencil). Lattices thin and deep, at thread counts that cut slabs into
// bands and that do not.
TEST(CountPassBlocks, BlocksOfAColourWriteDisjointCells) {
  for (const auto& [nx, ny, nz] : {std::array{30, 30, 30}, std::array{40, 40, 3}, std::array{6, 50, 40}})
    for (const int k : {1, 2})
      for (const int threads : {1, 2, 7, 16, 64}) {
        SCOPED_TRACE(std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz) + " k " +
                     std::to_string(k) + " threads " + std::to_string(threads));
        PointSet points{3, {}};
        for (int z = 0; z < nz; ++z)
          for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) points.xyz.insert(points.xyz.end(), {double(x), double(y), double(z)});
        const Grid grid = Grid::fit(points.view(), 1.5, k);
        const CellIndex index(points.view(), grid, 1);
        std::vector<int> blocks_of_cell(index.occupied_cells(), 0);
        std::int64_t lowest = grid.cells[1], highest = -1;  // occupied lines
        for (std::size_t c = 0; c < index.occupied_cells(); ++c) {
          lowest = std::min(lowest, index.cell_coord(c)[1]);
          highest = std::max(highest, index.cell_coord(c)[1]);
        }
        std::size_t bands_cut = 0;  // blocks of fewer lines than the slab
        for (const auto& colour : detail::count_pass_blocks(index, threads)) {
          std::map<std::array<std::int64_t, 2>, std::size_t> reached;  // (layer, line) -> block
          for (std::size_t b = 0; b < colour.size(); ++b) {
            std::set<std::array<std::int64_t, 2>> cells;
            std::int64_t low = highest, high = lowest;
            for (const detail::CellRun run : colour[b])
              for (std::size_t c = run.first; c < run.last; ++c) {
                ++blocks_of_cell[c];
                const auto [cz, cy, cx] = index.cell_coord(c);
                for (std::int64_t dz = 0; dz <= k; ++dz)
                  for (std::int64_t dy = -k; dy <= k; ++dy) cells.insert({cz + dz, cy + dy});
                low = std::min(low, cy);
                high = std::max(high, cy);
              }
            bands_cut += low > lowest || high < highest;
            for (const auto& cell : cells) {
              const auto [at, fresh] = reached.emplace(cell, b);
              EXPECT_TRUE(fresh) << "layer " << cell[0] << " line " << cell[1] << ": blocks " << at->second << ", " << b;
            }
          }
        }
        EXPECT_TRUE(std::all_of(blocks_of_cell.begin(), blocks_of_cell.end(), [](int n) { return n == 1; }));
        if (threads == 64 && nz == 30) EXPECT_GT(bands_cut, 0u);  // 64 threads: too few layers alone
      }
}

TEST(Backends, MoreThreadsThanPoints) {
  const PointSet points = random_cloud(5, 3, 4);
  SearchOptions options = options_for(20.0, Backend::openmp);
  options.threads = 16;
  const NeighborList list = search(points.view(), options);
  EXPECT_EQ(list.total(), 20);  // every pair within 20 in a cube of side 10
}

TEST(Backends, AFewPointsTestEveryPairAsTheOracleDoes) {
  // Up to 64 points the serial backend tests every pair without a grid: random, clustered
  // (duplicates: distance 0) and lattice points (pairs at exactly the horizon are out), 2-D and
  // 3-D, every metric, half lists, float32; 65 points take the grid, the same list.
  std::mt19937_64 rng(64);
  const Metric metrics[] = {Metric::euclidean, Metric::manhattan, Metric::chebyshev};
  for (std::size_t n : {0, 1, 2, 7, 31, 63, 64, 65}) {
    for (int dims : {2, 3}) {
      PointSet cloud = random_cloud(n, dims, rng());
      PointSet duplicates = cloud;
      for (std::size_t i = 1; i < n; i += 3)
        std::copy_n(&duplicates.xyz[0], dims, &duplicates.xyz[i * static_cast<std::size_t>(dims)]);
      PointSet grid{dims, {}};
      for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < dims; ++a) grid.xyz.push_back(static_cast<double>(i >> (2 * a) & 3));
      for (const PointSet* points : {&cloud, &duplicates, &grid})
        for (Metric metric : metrics)
          for (bool half : {false, true}) {
            SearchOptions options = options_for(points == &grid ? 1.0 : 4.0);
            options.metric = metric;
            options.half = half;
            const NeighborList list = search(points->view(), options);
            EXPECT_EQ(list, brute_force(points->view(), options)) << n << " points, " << dims << "-D";
            std::vector<float> single(points->xyz.begin(), points->xyz.end());
            const PointSet promoted{dims, std::vector<double>(single.begin(), single.end())};
            EXPECT_EQ(search(PointView(single.data(), n, dims), options), brute_force(promoted.view(), options));
          }
    }
  }
}

TEST(Backends, SmallSearchesFilledIntoRoomEqualTheOracle) {
  // Below 4,096 points one thread fills rows into room for their stencils (no count pass), or
  // counts first where a stencil holds 256 candidates or more (dense clusters): both as the
  // oracle, with half and unsorted rows, queries, every metric, 2-D and 3-D.
  const Metric metrics[] = {Metric::euclidean, Metric::manhattan, Metric::chebyshev};
  int problem = 0;
  for (std::size_t n : {65, 700, 4095, 4096})
    for (int dims : {2, 3})
      for (bool clustered : {false, true}) {
        const PointSet points = clustered ? clustered_cloud(n, 3, 0.05, dims, 9 + n) : random_cloud(n, dims, 9 + n);
        SearchOptions options = options_for(dims == 3 ? 1.2 : 0.5);
        options.metric = metrics[problem % 3];
        options.half = problem % 2 == 1;
        options.sort_rows = problem % 4 != 2;
        options.queries = problem % 5 == 3 ? n / 2 : 0;
        const NeighborList list = search(points.view(), options);
        const NeighborList expected = brute_force(points.view(), options);
        if (options.sort_rows) EXPECT_EQ(list, expected) << n << " points, " << dims << "-D, problem " << problem;
        else testing::expect_same_families(list, expected);
        ++problem;
      }
}

TEST(Backends, AutoPicksAnAvailableBackend) {
  SearchStats stats;
  const PointSet points = lattice(5);
  search(points.view(), options_for(2.5, Backend::automatic), &stats);
  EXPECT_NE(stats.backend, Backend::automatic);
  EXPECT_TRUE(backend_available(stats.backend));
}

TEST(Backends, AutoSearchesATinyProblemOnOneCore) {
  SearchStats stats;  // with a GPU too: its host path costs more than 100 points on one core
  const PointSet points = random_cloud(100, 3, 4);
  const NeighborList list = search(points.view(), options_for(2.0, Backend::automatic), &stats);
  EXPECT_EQ(stats.backend, Backend::serial) << stats.choice;
  EXPECT_EQ(stats.threads, 1);
  EXPECT_FALSE(stats.choice.empty());
  EXPECT_EQ(list, search(points.view(), options_for(2.0, Backend::serial)));
}

TEST(Backends, ThreadsStayWithinTheCpusOfTheAffinityMask) {
  cpu_set_t saved, one;
  ASSERT_EQ(sched_getaffinity(0, sizeof saved, &saved), 0);
  CPU_ZERO(&one);
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &saved)) {
      CPU_SET(cpu, &one);
      break;
    }
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);  // this thread may run on one CPU only
  const PointSet points = random_cloud(200000, 3, 6);
  SearchStats openmp, automatic;
  const NeighborList list = search(points.view(), options_for(0.3, Backend::openmp), &openmp);
  if (!backend_available(Backend::cuda)) search(points.view(), options_for(0.3, Backend::automatic), &automatic);
  sched_setaffinity(0, sizeof saved, &saved);
  EXPECT_EQ(openmp.threads, 1);
  if (!backend_available(Backend::cuda)) {
    EXPECT_EQ(automatic.backend, Backend::serial) << automatic.choice;
    EXPECT_EQ(automatic.threads, 1);
  }
  EXPECT_EQ(list, search(points.view(), options_for(0.3, Backend::serial)));
}

TEST(Backends, WarmUpLeavesEveryBackendReady) {
  warm_up(Backend::automatic);
  warm_up(Backend::serial);
  warm_up(Backend::openmp);
  if (backend_available(Backend::cuda)) warm_up(Backend::cuda);
  else EXPECT_THROW(warm_up(Backend::cuda), Error);
}

TEST(Input, Float32GivesTheSameListAsFloat64OfTheSameValues) {
  const PointSet points = random_cloud(3000, 3, 8);
  std::vector<float> single(points.xyz.begin(), points.xyz.end());
  PointSet promoted{3, std::vector<double>(single.begin(), single.end())};
  const auto options = options_for(0.9);
  EXPECT_EQ(search(PointView(single.data(), 3000, 3), options), search(promoted.view(), options));
}

TEST(Options, UnsortedRowsHoldTheSameFamilies) {
  const PointSet points = random_cloud(5000, 3, 6);
  SearchOptions options = options_for(0.8);
  const NeighborList sorted = search(points.view(), options);
  options.sort_rows = false;
  testing::expect_same_families(search(points.view(), options), sorted);
}

TEST(Options, QueriesGetRowsAndTheRestAreReferencesOnly) {
  const PointSet points = random_cloud(4000, 3, 12);
  for (bool half : {false, true})
    for (Backend backend : {Backend::serial, Backend::openmp}) {
      SearchOptions options = options_for(0.9, backend);
      options.half = half;
      const NeighborList all = search(points.view(), options);
      options.queries = 1500;
      const NeighborList some = search(points.view(), options);
      for (std::size_t i = 0; i < points.size(); ++i) {
        if (i < 1500)
          EXPECT_TRUE(std::equal(all.row(i).begin(), all.row(i).end(), some.row(i).begin(), some.row(i).end()));
        else
          EXPECT_EQ(some.row_size(i), 0u);
      }
    }
}

TEST(Options, HalfListHoldsEachPairOnce) {
  const PointSet points = random_cloud(4000, 3, 2);
  SearchOptions options = options_for(0.9);
  const NeighborList full = search(points.view(), options);
  options.half = true;
  const NeighborList half = search(points.view(), options);
  EXPECT_EQ(2 * half.total(), full.total());
  for (std::size_t i = 0; i < half.size(); ++i)
    for (point_id j : half.row(i)) EXPECT_GT(j, static_cast<point_id>(i));
}

TEST(Options, HorizonWhoseSquareUnderflowsMatchesBruteForce) {
  // δ² = 0 in double: no Euclidean pair passes, not even coincident points; the full-list
  // kernels that drop `self` after the tests must not drop it then.
  const PointSet points{3, {0, 0, 0, 0, 0, 0, 1e-171, 0, 0, 5, 5, 5, 5, 5, 5}};
  for (Backend backend : {Backend::serial, Backend::openmp})
    for (Metric metric : {Metric::euclidean, Metric::manhattan, Metric::chebyshev})
      for (bool sorted : {true, false}) {
        SearchOptions options = options_for(1e-170, backend);
        options.metric = metric;
        options.sort_rows = sorted;
        const NeighborList list = search(points.view(), options);
        testing::expect_same_families(list, brute_force(points.view(), options));
      }
}

TEST(Grid, HugeExtentStaysSparseAndSmall) {
  PointSet points{3, {0, 0, 0, 1e12, 1e12, 1e12, 1e12 + 2e-4, 1e12, 1e12}};
  const Grid grid = Grid::fit(points.view(), 1e-3, 1);
  EXPECT_FALSE(grid.dense);
  const NeighborList list = search(points.view(), options_for(1e-3));
  EXPECT_EQ(list.total(), 2);
  EXPECT_EQ(list.row_size(0), 0u);
}

// One far outlier makes a clustered cloud's grid sparse (rows of cells in a hash table, columns
// in a table or found by binary search): every backend, k, metric and list shape as the oracle.
TEST(Grid, AFarOutlierMakesTheGridSparseAndTheListsStayExact) {
  for (int dims : {2, 3}) {
    PointSet points = clustered_cloud(3000, 4, 0.3, dims, 5);
    for (int a = 0; a < dims; ++a) points.xyz.push_back(1e6);
    for (Metric metric : {Metric::euclidean, Metric::chebyshev})
      for (bool half : {false, true}) {
        SearchOptions options = options_for(0.2);
        options.metric = metric;
        options.half = half;
        options.threads = 3;
        const NeighborList expected = brute_force(points.view(), options);
        for (int k = 1; k <= 3; ++k) {
          ASSERT_FALSE(Grid::fit(points.view(), 0.2, k).dense);
          options.cells_per_horizon = k;
          for (Backend backend : {Backend::serial, Backend::openmp}) {
            options.backend = backend;
            EXPECT_EQ(search(points.view(), options), expected)
                << dims << "-D k " << k << " " << metric_name(metric) << (half ? " half" : "");
          }
        }
      }
  }
}

// Cell coordinates are (x - origin) * (1 / side), three roundings: the side's widening by 2^-49
// of the extent must keep every pair closer than the horizon within k cells, wherever the points
// lie. The hardest pairs: the first point a few ulps from a cell's face, the second a few ulps
// less than the horizon away. Without the widening some are k + 1 cells apart (the first one
// found: a = 0.442, b = 0.443 less an ulp, horizon 0.001, k = 2, in the unit box).
TEST(Grid, PairsInsideTheHorizonAreAtMostKCellsApartWhereverThePointsLie) {
  std::mt19937_64 random(11);
  auto ulps = [](double x, int n) {
    for (int i = 0; i < std::abs(n); ++i) x = std::nextafter(x, n < 0 ? -HUGE_VAL : HUGE_VAL);
    return x;
  };
  for (const double offset : {0.0, 0.1, 12345.678, -7e6, 1e9, -1e12})
    for (const double extent : {1.0, 10.0, 1e4, 3.3e7})
      for (const double horizon : {1e-3 * extent, 0.037 * extent, 0.37 * extent, 0.3015})
        for (int k = 1; k <= 3; ++k) {
          Bounds box;
          box.lo = {offset, offset, offset};
          box.hi = {offset + extent, offset + extent, offset + extent};
          const Grid grid = Grid::from_bounds(box, 3, 2, horizon, k);
          const auto faces = static_cast<std::uint64_t>(extent / grid.cell_side);
          if (faces < 2) continue;
          for (int trial = 0; trial < 300; ++trial) {
            const double face = offset + static_cast<double>(random() % faces) * grid.cell_side;
            for (int from_face = -6; from_face <= 6; ++from_face) {
              const double a = ulps(face, from_face);
              for (int short_of = 1; short_of <= 8; ++short_of) {
                const double b = ulps(a + horizon, -short_of);
                if (!(b - a < horizon)) continue;
                ASSERT_LE(grid.cell_of(b, 0) - grid.cell_of(a, 0), k)
                    << "a " << a << " b " << b << " horizon " << horizon << " k " << k;
              }
            }
          }
        }
}

TEST(Errors, BadInputIsNamed) {
  PointSet points{3, {0, 0, 0, 1, std::nan(""), 0}};
  try {
    search(points.view(), options_for(1.0));
    FAIL() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("point 1"), std::string::npos) << e.what();
  }
  points.xyz[4] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(search(points.view(), options_for(1.0)), Error);
  points.xyz[4] = 0;
  for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(search(points.view(), options_for(bad)), Error) << bad;
  EXPECT_THROW(search(points.view(), options_for(1.0, Backend::serial, 4)), Error);
  EXPECT_THROW(search(PointView(points.xyz.data(), 1, 4), options_for(1.0)), Error);
  SearchOptions too_many = options_for(1.0);
  too_many.queries = 3;
  EXPECT_THROW(search(points.view(), too_many), Error);
}

TEST(Errors, EmptyInputGivesAnEmptyList) {
  const PointSet none{3, {}};
  const NeighborList list = search(none.view(), options_for(1.0));
  EXPECT_EQ(list.size(), 0u);
  EXPECT_EQ(list.total(), 0);
}

}  // namespace
}  // namespace horizon

namespace horizon {
namespace {
TEST(Memory, ListTooLargeIsRefusedBeforeAllocatingWithItsSizeAndTheWaysOut) {
  const PointSet points = lattice(30);
  for (Backend backend : {Backend::serial, Backend::openmp}) {
    SearchOptions options;
    options.horizon = 3.015 * 10.0 / 30;
    options.backend = backend;
    options.max_memory = 100000;  // bytes
    try {
      search(points.view(), options);
      FAIL() << "a list larger than max_memory was built";
    } catch (const ListTooLarge& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.bytes_needed, static_cast<std::size_t>(lattice_entries(30, 3, 3.015)) * 4) << what;
      EXPECT_NE(what.find("--half"), std::string::npos) << what;
    }
    options.max_memory = std::size_t{1} << 30;
    EXPECT_EQ(search(points.view(), options).total(), lattice_entries(30, 3, 3.015));
  }
}
}  // namespace
}  // namespace horizon

namespace horizon {
namespace {

TEST(Validate, NamesTheFirstNonFinitePointOnAnyBackendAndPrecision) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (double bad : {nan, inf, -inf})
    for (std::size_t at : {std::size_t{0}, std::size_t{70000}, std::size_t{399999}}) {
      PointSet points = random_cloud(400000, 3, 1);
      points.xyz[at * 3 + 2] = bad;
      if (at > 0) points.xyz[(at + 1 < 400000 ? at + 1 : at) * 3] = bad;  // a later one is not named
      const std::vector<float> single(points.xyz.begin(), points.xyz.end());
      const std::string expected = "point " + std::to_string(at) + " has a non-finite coordinate";
      // One GPU tests the values once uploaded, not the host: the same message.
      std::vector<Backend> backends{Backend::serial, Backend::openmp};
      if (backend_available(Backend::cuda)) backends.push_back(Backend::cuda);
      for (const Backend backend : backends)
        for (const bool periodic : {false, true}) {
          SearchOptions options;
          options.horizon = 0.1;
          options.backend = backend;
          if (periodic) options.box = {10, 10, 10};
          for (const PointView view : {points.view(), PointView(single.data(), 400000, 3)}) {
            try {
              search(view, options);
              ADD_FAILURE() << "accepted a non-finite coordinate at point " << at;
            } catch (const Error& e) {
              EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
            }
          }
        }
    }
}

}  // namespace
}  // namespace horizon
