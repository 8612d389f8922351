// The distributed search under mpirun: for every exchange strategy and decomposition, the rows
// gathered from all ranks equal the serial list exactly.
#include <gtest/gtest.h>
#include <mpi.h>

#include <fstream>
#include <iterator>
#include <random>

#include "datasets.hpp"
#include "random_cells.hpp"
#include "random_problems.hpp"
#include "horizon/oracle.hpp"
#include "horizon/distributed.hpp"
#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/grid.hpp"
#include "horizon/io.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"

namespace horizon::testing {
namespace {

int rank_id() {
  int id = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &id);
  return id;
}

int rank_count() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

// Brute force's list, on rank 0 only (the others get an empty list): computed once, compared with
// every strategy.
NeighborList oracle_on_root(const PointSet& points, SearchOptions options) {
  if (rank_id() != 0) return {};
  options.backend = Backend::serial;
  return brute_force(points.view(), options);
}

// The block of `points` (and of `radii`, if any) this rank holds, with global ids; everything with
// overlap.
PointSet held_block(const PointSet& points, const DistributedOptions& options, std::vector<std::int64_t>& ids,
                    const std::vector<double>* radii = nullptr, std::vector<double>* held_radii = nullptr) {
  if (options.exchange == Exchange::overlap) {
    if (radii) *held_radii = *radii;
    return points;
  }
  const std::size_t n = points.size();
  const std::size_t p = static_cast<std::size_t>(rank_count()), r = static_cast<std::size_t>(rank_id());
  PointSet held{points.dims, {}};
  for (std::size_t i = n * r / p; i < n * (r + 1) / p; ++i) {
    ids.push_back(static_cast<std::int64_t>(i));
    for (int a = 0; a < points.dims; ++a) held.xyz.push_back(points.xyz[i * points.dims + a]);
    if (radii) held_radii->push_back((*radii)[i]);
  }
  return held;
}

// Per-point radii and their rule, for matches_serial.
struct Radii {
  const std::vector<double>& values;
  RadiusRule rule;
};

// The distributed list of `data`, gathered on rank 0, compared there with the serial list (or
// with `expected`, brute force's list from oracle_on_root); every rank learns the verdict.
bool matches_serial(const PointSet& points, const DistributedOptions& options, DistributedStats* stats = nullptr,
                    const NeighborList* expected = nullptr, const Radii* radii = nullptr) {
  const std::size_t n = points.size();
  std::vector<std::int64_t> ids;
  std::vector<double> held_radii;
  const PointSet held = held_block(points, options, ids, radii ? &radii->values : nullptr, &held_radii);
  const OwnedRows rows =
      radii ? search_distributed(MPI_COMM_WORLD, held.view(), ids, held_radii, radii->rule, n, options, stats)
            : search_distributed(MPI_COMM_WORLD, held.view(), ids, n, options, stats);
  const NeighborList gathered = gather_rows(MPI_COMM_WORLD, rows, n, options.search.half);
  int same = 1;
  if (rank_id() == 0) {
    SearchOptions serial = options.search;
    serial.backend = Backend::serial;
    same = expected ? gathered == *expected : gathered == search(points.view(), serial);
  }
  MPI_Bcast(&same, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return same == 1;
}

// The distributed rows of `queries` among `references`, gathered on rank 0 and compared there
// with `expected`; every rank learns the verdict.
bool queries_match(const PointSet& queries, const PointSet& references, const DistributedOptions& options,
                   const NeighborList& expected, const std::vector<double>* radii = nullptr) {
  std::vector<std::int64_t> query_ids, reference_ids;
  std::vector<double> held_radii;
  const PointSet held_queries = held_block(queries, options, query_ids, radii, &held_radii);
  const PointSet held_references = held_block(references, options, reference_ids);
  const OwnedRows rows =
      search_distributed_queries(MPI_COMM_WORLD, held_queries.view(), query_ids, queries.size(),
                                 held_references.view(), reference_ids, references.size(), options, held_radii);
  const NeighborList gathered = gather_rows(MPI_COMM_WORLD, rows, queries.size(), false);
  int same = rank_id() == 0 ? gathered == expected : 1;
  MPI_Bcast(&same, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return same == 1;
}

struct Strategy {
  Exchange exchange;
  Decomposition::Kind decomposition;
};

const Strategy strategies[] = {{Exchange::thesis, Decomposition::Kind::rcb},
                               {Exchange::halo, Decomposition::Kind::rcb},
                               {Exchange::halo, Decomposition::Kind::brick},
                               {Exchange::overlap, Decomposition::Kind::rcb},
                               {Exchange::overlap, Decomposition::Kind::brick}};

std::string describe(const Strategy& s) {
  return std::string(exchange_name(s.exchange)) + (s.decomposition == Decomposition::Kind::rcb ? "/rcb" : "/brick");
}

TEST(Distributed, EveryStrategyEqualsSerialOnEveryDataset) {
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims))
      for (const Strategy& s : strategies) {
        DistributedOptions options;
        options.search.horizon = data.horizon;
        options.search.backend = Backend::serial;
        options.exchange = s.exchange;
        options.decomposition = s.decomposition;
        EXPECT_TRUE(matches_serial(data.points, options)) << data.name << " " << dims << "-D " << describe(s);
      }
}

TEST(Distributed, HalfListsOtherMetricsAndOpenmp) {
  const PointSet points = clustered_cloud(4000, 5, 0.5, 3, 8);
  for (const Strategy& s : strategies)
    for (Metric metric : {Metric::manhattan, Metric::chebyshev}) {
      DistributedOptions options;
      options.search.horizon = 0.3;
      options.search.metric = metric;
      options.search.half = true;
      options.search.cells_per_horizon = 2;
      options.search.backend = Backend::openmp;
      options.exchange = s.exchange;
      options.decomposition = s.decomposition;
      EXPECT_TRUE(matches_serial(points, options)) << describe(s) << " " << metric_name(metric);
    }
}

TEST(Distributed, MoreRanksThanPointsOrCells) {
  // 3 points, and a lattice of 8 cells: some ranks own nothing at all.
  const PointSet few{3, {0, 0, 0, 0.5, 0, 0, 5, 5, 5}};
  const PointSet small = lattice(2);
  for (const Strategy& s : strategies)
    for (const PointSet* points : {&few, &small}) {
      DistributedOptions options;
      options.search.horizon = 6.0;
      options.exchange = s.exchange;
      options.decomposition = s.decomposition;
      EXPECT_TRUE(matches_serial(*points, options)) << describe(s);
    }
}

TEST(Distributed, PointsOnSubdomainBorders) {
  // A lattice whose coordinates fall exactly on brick cuts for 2, 4 and 8 slabs: spacing 1 from
  // 0 to 16, cuts at multiples of 16/p.
  PointSet grid{3, {}};
  for (int k = 0; k <= 16; k += 2)
    for (int j = 0; j <= 16; ++j)
      for (int i = 0; i <= 16; ++i) grid.xyz.insert(grid.xyz.end(), {double(i), double(j), double(k)});
  for (const Strategy& s : strategies) {
    DistributedOptions options;
    options.search.horizon = 2.0;  // exact ties at distance 2 are excluded everywhere
    options.exchange = s.exchange;
    options.decomposition = s.decomposition;
    DistributedStats stats;
    EXPECT_TRUE(matches_serial(grid, options, &stats)) << describe(s);
    EXPECT_EQ(stats.ranks, rank_count());
    if (rank_count() > 1 && s.exchange != Exchange::overlap) EXPECT_GT(stats.bytes_sent, 0) << describe(s);
    if (s.exchange == Exchange::overlap) EXPECT_EQ(stats.bytes_sent, 0);
  }
}

TEST(Distributed, PeriodicBoxesOnEveryDataset) {
  // Each dataset wrapped into a box just larger than its extent (periodic on every axis, then
  // on x only), the horizon kept below half of each period: pairs across the faces.
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims)) {
      PointSet points = data.points;
      const Bounds bounds = bounds_of(points.view());
      std::array<double, 3> period{0, 0, 0};
      for (int a = 0; a < dims; ++a) period[a] = std::max(bounds.hi[a] - bounds.lo[a], 2.5 * data.horizon) * 1.01;
      for (std::size_t i = 0; i < points.size(); ++i)
        for (int a = 0; a < dims; ++a) points.xyz[i * dims + a] -= bounds.lo[a];
      for (const bool x_only : {false, true}) {
        DistributedOptions options;
        options.search.horizon = data.horizon;
        options.search.box = period;
        if (x_only) options.search.box[1] = options.search.box[2] = 0;
        options.search.half = x_only;
        const NeighborList expected = oracle_on_root(points, options.search);
        for (const Strategy& s : strategies) {
          options.exchange = s.exchange;
          options.decomposition = s.decomposition;
          EXPECT_TRUE(matches_serial(points, options, nullptr, &expected))
              << data.name << " " << dims << "-D " << describe(s) << (x_only ? " x periodic, half" : "");
        }
      }
    }
}

TEST(Distributed, PerPointRadiiOnEveryDataset) {
  // Radii over 10x the dataset's horizon, each rule (a half list with max), against the one-node
  // search_with_radii (itself checked against brute force in radii_test.cpp), the strategies
  // taken in turn (every rule meets every strategy over the datasets); then a periodic box
  // against brute force, every strategy.
  std::size_t turn = 0;
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims)) {
      if (data.name == "huge_extent" || data.name == "dense") continue;  // as in radii_test.cpp
      std::mt19937_64 rng(31);
      std::uniform_real_distribution<double> exponent(std::log(0.3), std::log(3.0));
      std::vector<double> radii(data.points.size());
      for (double& r : radii) r = data.horizon * std::exp(exponent(rng));
      for (const auto& [rule, half] : {std::pair{RadiusRule::gather, false}, std::pair{RadiusRule::scatter, false},
                                       std::pair{RadiusRule::max, true}, std::pair{RadiusRule::min, false}}) {
        DistributedOptions options;
        options.search.half = half;
        const NeighborList expected = rank_id() == 0 ? search_with_radii(data.points.view(), radii, rule, options.search)
                                                     : NeighborList{};
        const Radii given{radii, rule};
        const Strategy& s = strategies[turn++ % std::size(strategies)];
        options.exchange = s.exchange;
        options.decomposition = s.decomposition;
        EXPECT_TRUE(matches_serial(data.points, options, nullptr, &expected, &given))
            << data.name << " " << dims << "-D " << describe(s) << " " << radius_rule_name(rule);
      }
    }
  // A periodic box (x and y), radii 0.4-2.4, max rule, against brute force.
  PointSet points = random_cloud(600, 3, 23);
  std::vector<double> radii(points.size());
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> radius(0.4, 2.4);
  for (double& r : radii) r = radius(rng);
  DistributedOptions options;
  options.search.box = {10, 10, 0};
  const NeighborList expected =
      rank_id() == 0 ? brute_force_with_radii(points.view(), radii, RadiusRule::max, options.search) : NeighborList{};
  const Radii given{radii, RadiusRule::max};
  for (const Strategy& s : strategies) {
    options.exchange = s.exchange;
    options.decomposition = s.decomposition;
    EXPECT_TRUE(matches_serial(points, options, nullptr, &expected, &given)) << "periodic " << describe(s);
  }
}

TEST(Distributed, QueriesAmongReferencesOnEveryDataset) {
  // 400 queries (a quarter of them on reference points: nothing is excluded as self) against each
  // dataset, with one horizon and with a radius per query (over 10x), the strategies in turn,
  // against the one-node query search; then in a periodic box against brute force.
  std::size_t turn = 0;
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims)) {
      PointSet queries = random_cloud(300, dims, 41);
      const std::size_t on_points = std::min<std::size_t>(100, data.points.size());
      queries.xyz.insert(queries.xyz.end(), data.points.xyz.begin(),
                         data.points.xyz.begin() + static_cast<std::ptrdiff_t>(on_points * dims));
      std::mt19937_64 rng(43);
      std::uniform_real_distribution<double> exponent(std::log(0.3), std::log(3.0));
      std::vector<double> radii(queries.size());
      for (double& r : radii) r = data.horizon * std::exp(exponent(rng));
      for (const bool with_radii : {false, true}) {
        if (with_radii && (data.name == "huge_extent" || data.name == "dense")) continue;  // as in radii_test.cpp
        DistributedOptions options;
        options.search.horizon = data.horizon;
        NeighborList expected;
        if (rank_id() == 0)
          expected = with_radii ? search_with_radii(queries.view(), radii, data.points.view(), options.search)
                                : search(queries.view(), data.points.view(), options.search);
        const Strategy& s = strategies[turn++ % std::size(strategies)];
        options.exchange = s.exchange;
        options.decomposition = s.decomposition;
        EXPECT_TRUE(queries_match(queries, data.points, options, expected, with_radii ? &radii : nullptr))
            << data.name << " " << dims << "-D " << describe(s) << (with_radii ? " radii" : "");
      }
    }
  const PointSet references = random_cloud(600, 3, 23), queries = random_cloud(200, 3, 29);
  DistributedOptions options;
  options.search.horizon = 1.5;
  options.search.box = {10, 10, 0};
  const NeighborList expected =
      rank_id() == 0 ? brute_force(queries.view(), references.view(), options.search) : NeighborList{};
  for (const Strategy& s : strategies) {
    options.exchange = s.exchange;
    options.decomposition = s.decomposition;
    EXPECT_TRUE(queries_match(queries, references, options, expected)) << "periodic " << describe(s);
  }
}

TEST(Distributed, CellsEqualTheOracleWithTheirGeometry) {
  // Random cells (some nearly degenerate), horizons of several cells, points anywhere, shifts,
  // distances and vectors, half lists and self_interaction: every strategy, as on one node.
  std::mt19937_64 rng(5800);
  const Metric metrics[] = {Metric::euclidean, Metric::euclidean, Metric::manhattan, Metric::chebyshev};
  for (int problem = 0; problem < 20; ++problem) {
    const int dims = problem % 4 == 3 ? 2 : 3;
    const Cell cell = random_cell(rng, dims, problem % 5 == 0 ? 0.05 : 0.3);
    // A few points (all tested against all on a rank) to a few hundred (the grid's search).
    const std::size_t n = problem % 3 == 0 ? 1 + rng() % 12 : 100 + rng() % 300;
    const PointSet points = points_around(cell, dims, n, rng);
    const Strategy& s = strategies[static_cast<std::size_t>(problem) % std::size(strategies)];
    DistributedOptions options;
    options.exchange = s.exchange;
    options.decomposition = s.decomposition;
    options.search.backend = problem % 2 ? Backend::openmp : Backend::serial;
    options.search.cell = cell;
    options.search.metric = metrics[problem % 4];
    options.search.horizon = std::uniform_real_distribution<double>(0.3, n < 20 ? 4.0 : 1.5)(rng);
    options.search.half = problem % 3 == 1;
    options.search.self_interaction = problem % 4 == 0;
    options.search.outputs = {problem % 5 != 1, true, problem % 5 != 2};
    const NeighborList expected = oracle_on_root(points, options.search);
    EXPECT_TRUE(matches_serial(points, options, nullptr, &expected))
        << "problem " << problem << ", " << dims << "-D, " << n << " points, horizon " << options.search.horizon
        << ", " << describe(s);
  }
}

TEST(Distributed, CellsWithPerAtomRadiiAndOutputsOfABox) {
  std::mt19937_64 rng(5801);
  for (int problem = 0; problem < 8; ++problem) {
    const Cell cell = random_cell(rng, 3, 0.3);
    const PointSet points = points_around(cell, 3, 20 + rng() % 200, rng);
    std::vector<double> radii(points.size());
    for (double& r : radii) r = std::uniform_real_distribution<double>(0.1, 0.8)(rng);
    DistributedOptions options;
    options.exchange = strategies[static_cast<std::size_t>(problem) % std::size(strategies)].exchange;
    options.search.cell = cell;
    options.search.half = problem % 2 == 0;
    options.search.outputs.distances = true;
    const RadiusRule rule = problem % 3 == 0 ? RadiusRule::max : RadiusRule::sum;
    const Radii with{radii, rule};
    NeighborList expected;
    if (rank_id() == 0) expected = brute_force_with_radii(points.view(), radii, rule, options.search);
    EXPECT_TRUE(matches_serial(points, options, nullptr, &expected, &with)) << "radii, problem " << problem;
  }
  // An orthorhombic box with outputs takes the same path.
  const PointSet cubes = lattice(6, 3, 6.0);
  DistributedOptions options;
  options.search.horizon = 1.5;
  options.search.box = {6, 6, 6};
  options.search.outputs = {true, true, true};
  EXPECT_TRUE(matches_serial(cubes, options)) << "box with outputs";
}

TEST(Distributed, CellsOnSeveralThreadsPerRankEqualOneNode) {
  // Enough rows per rank (over 512) for the measuring passes to run on both threads.
  std::mt19937_64 rng(5803);
  const Cell cell = random_cell(rng, 3, 0.4);
  const PointSet points = points_around(cell, 3, 2500, rng);
  DistributedOptions options;
  options.search.cell = cell;
  options.search.horizon = 0.6;
  options.search.backend = Backend::openmp;
  options.search.threads = 2;
  options.search.outputs = {true, true, true};
  EXPECT_TRUE(matches_serial(points, options)) << "2 threads a rank";
}

TEST(Distributed, CellGeometryFilesEqualTheSerialWriter) {
  std::mt19937_64 rng(5802);
  const Cell cell = random_cell(rng, 3, 0.3);
  const PointSet points = points_around(cell, 3, 150, rng);
  DistributedOptions options;
  options.search.cell = cell;
  options.search.horizon = 1.2;
  options.search.outputs = {true, true, true};
  std::vector<std::int64_t> ids;
  const PointSet held = held_block(points, options, ids);
  const OwnedRows rows = search_distributed(MPI_COMM_WORLD, held.view(), ids, points.size(), options);
  const std::string directory = ::testing::TempDir();
  const std::string parallel = directory + "/cell_parallel", serial = directory + "/cell_serial";
  const std::string written = write_rows_parallel(MPI_COMM_WORLD, rows, points.size(), parallel);
  const NeighborList gathered = gather_rows(MPI_COMM_WORLD, rows, points.size(), false);
  int same = 1;
  if (rank_id() == 0) {
    const std::string expected = write_neighbor_list(serial, gathered, ListFormat::npy);
    EXPECT_EQ(written, parallel + ".offsets.npy," + parallel + ".indices.npy," + parallel + ".shifts.npy," + parallel +
                           ".distances.npy," + parallel + ".vectors.npy");
    EXPECT_EQ(expected.size(), written.size() - parallel.size() * 5 + serial.size() * 5);
    for (const char* suffix : {".offsets.npy", ".indices.npy", ".shifts.npy", ".distances.npy", ".vectors.npy"}) {
      std::ifstream a(parallel + suffix, std::ios::binary), b(serial + suffix, std::ios::binary);
      const std::string x((std::istreambuf_iterator<char>(a)), {}), y((std::istreambuf_iterator<char>(b)), {});
      same = same && !x.empty() && x == y;
      EXPECT_EQ(x, y) << suffix;
    }
  }
  MPI_Bcast(&same, 1, MPI_INT, 0, MPI_COMM_WORLD);
  EXPECT_EQ(same, 1);
}

TEST(Distributed, CellIdsOutsideTheRangeAreRefusedOnEveryRank) {
  const PointSet points = lattice(4, 3, 4.0);
  DistributedOptions options;
  options.search.horizon = 1.5;
  options.search.cell = Cell::orthorhombic({4, 4, 4});
  std::vector<std::int64_t> ids;
  const PointSet held = held_block(points, options, ids);
  for (std::int64_t& id : ids) id += 1;  // the last rank's last id is out of [0, n)
  try {
    search_distributed(MPI_COMM_WORLD, held.view(), ids, points.size(), options);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("global id 64, not in [0, 64)"), std::string::npos) << e.what();
  }
}

TEST(Distributed, RandomProblemsAgreeWithTheOracle) {
  // The differential problems of differential_test.cpp, at 2 and 3 ranks, each strategy in turn.
  if (rank_count() != 2 && rank_count() != 3) GTEST_SKIP() << "runs at 2 and 3 ranks";
  std::mt19937_64 rng(seed());
  for (int n = 0; n < problem_count(200); ++n) {  // fewer than on one node: each runs at 2 and 3 ranks
    Problem p = draw(rng);
    p.options.queries = 0;       // every point of a distributed search gets its row
    const Strategy& s = strategies[static_cast<std::size_t>(n) % std::size(strategies)];
    DistributedOptions options;
    options.search = p.options;
    options.search.backend = Backend::serial;
    options.exchange = s.exchange;
    options.decomposition = s.decomposition;
    const PointSet points{p.dims, p.xyz};
    const NeighborList expected = oracle_on_root(points, options.search);
    ASSERT_TRUE(matches_serial(points, options, nullptr, &expected))
        << "problem " << n << " of seed " << seed() << " (" << p.describe() << "), " << describe(s);
  }
}

}  // namespace
}  // namespace horizon::testing

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (horizon::testing::rank_id() != 0) {  // one report, from rank 0
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int status = RUN_ALL_TESTS();
  int worst = 0;
  MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
