// Periodic cells of any shape (SearchOptions::cell): every backend against the cell oracle on
// random cells, including nearly degenerate ones and horizons of several cells; closed-form
// image counts; the orthorhombic box's answer; and the errors of bad cells.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <tuple>
#include <random>
#include <string>

#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/oracle.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"
#include "random_cells.hpp"

namespace horizon {
namespace {

using testing::points_around;
using testing::random_cell;

std::vector<Backend> cpu_and_gpu() {
  std::vector<Backend> backends{Backend::serial, Backend::automatic};
  if (backend_available(Backend::openmp)) backends.push_back(Backend::openmp);
  if (backend_available(Backend::cuda)) backends.push_back(Backend::cuda);
  return backends;
}

/// Where two lists first differ: the row, and the entries (j and shift) from the first difference on.
std::string first_difference(const NeighborList& got, const NeighborList& expected) {
  if (got == expected) return "equal";
  auto entries = [](const NeighborList& list, std::size_t i) {
    std::vector<std::string> text;
    const std::size_t dims = list.indices().empty() ? 0 : list.shifts().size() / list.indices().size();
    for (auto e = list.offsets()[i]; e < list.offsets()[i + 1]; ++e) {
      std::string entry = std::to_string(list.indices()[e]);
      for (std::size_t a = 0; a < dims; ++a) entry += (a ? "," : "(") + std::to_string(list.shifts()[e * dims + a]);
      text.push_back(entry + (dims ? ")" : ""));
    }
    return text;
  };
  for (std::size_t i = 0; i < std::min(got.size(), expected.size()); ++i) {
    const auto g = entries(got, i), x = entries(expected, i);
    if (g == x) continue;
    std::size_t at = 0;
    while (at < g.size() && at < x.size() && g[at] == x[at]) ++at;
    std::string text = "row " + std::to_string(i) + " from entry " + std::to_string(at) + " of " +
                       std::to_string(g.size()) + " (expected " + std::to_string(x.size()) + "):\n got";
    for (std::size_t k = at; k < std::min(g.size(), at + 6); ++k) text += " " + g[k];
    text += "\n expected";
    for (std::size_t k = at; k < std::min(x.size(), at + 6); ++k) text += " " + x[k];
    return text;
  }
  return got.size() != expected.size() ? "row counts differ" : "the ids agree; distances or vectors differ";
}

TEST(CellSearch, RandomCellsEqualTheOracleOnEveryBackend) {
  std::mt19937_64 rng(58);
  const Metric metrics[] = {Metric::euclidean, Metric::euclidean, Metric::manhattan, Metric::chebyshev};
  for (int problem = 0; problem < 60; ++problem) {
    const int dims = problem % 3 == 0 ? 2 : 3;
    const Cell cell = random_cell(rng, dims, problem % 5 == 0 ? 0.05 : 0.3);
    const PointSet points = points_around(cell, dims, 1 + rng() % (dims == 3 ? 40 : 60), rng);
    SearchOptions options;
    options.cell = cell;
    options.metric = metrics[problem % 4];
    options.horizon = std::uniform_real_distribution<double>(0.3, dims == 3 ? 4.0 : 6.0)(rng);  // up to a few cells
    options.half = problem % 2 == 1;
    options.self_interaction = problem % 7 == 0;
    options.outputs = {true, true, true};
    options.cells_per_horizon = 1 + problem % 2;
    const NeighborList expected = brute_force(points.view(), options);
    for (Backend backend : cpu_and_gpu()) {
      options.backend = backend;
      const NeighborList got = search(points.view(), options);
      EXPECT_TRUE(got == expected) << first_difference(got, expected) << "\nproblem " << problem << " on " << backend_name(backend) << ", " << dims << "-D, horizon " << options.horizon;
    }
  }
}

TEST(CellSearch, LargerSystemsTakeTheGridAndEqualTheOracle) {
  // Hundreds of points and their images: the engine's grid finds the candidates (a few dozen
  // points and images are tested all against all instead).
  std::mt19937_64 rng(580);
  for (int problem = 0; problem < 12; ++problem) {
    const int dims = problem % 4 == 0 ? 2 : 3;
    const Cell cell = random_cell(rng, dims, problem % 3 == 0 ? 0.1 : 0.4);
    const PointSet points = points_around(cell, dims, 150 + rng() % 150, rng);
    SearchOptions options;
    options.cell = cell;
    options.horizon = std::uniform_real_distribution<double>(0.5, 2.5)(rng);
    options.half = problem % 2 == 1;
    options.outputs = {problem % 3 != 1, true, problem % 3 != 2};
    const NeighborList expected = brute_force(points.view(), options);
    for (Backend backend : cpu_and_gpu()) {
      options.backend = backend;
      SearchStats stats;
      const NeighborList got = search(points.view(), options, &stats);
      EXPECT_TRUE(got == expected) << first_difference(got, expected) << "\nproblem " << problem;
      if (backend != Backend::automatic) EXPECT_EQ(stats.backend, backend) << "the grid ran on the backend asked for";
    }
  }
}

TEST(CellSearch, PerAtomRadiiEqualTheOracle) {
  std::mt19937_64 rng(5858);
  for (int problem = 0; problem < 20; ++problem) {
    const Cell cell = random_cell(rng, 3, 0.3);
    const PointSet points = points_around(cell, 3, 2 + rng() % 30, rng);
    std::vector<double> radii(points.size());
    for (double& r : radii) r = std::uniform_real_distribution<double>(0.2, 1.5)(rng);
    SearchOptions options;
    options.cell = cell;
    options.half = problem % 2 == 0;
    options.outputs.distances = true;
    const RadiusRule rule = problem % 3 == 0 ? RadiusRule::max : RadiusRule::sum;
    const NeighborList expected = brute_force_with_radii(points.view(), radii, rule, options);
    for (Backend backend : cpu_and_gpu()) {
      options.backend = backend;
      const NeighborList got = search_with_radii(points.view(), radii, rule, options);
      EXPECT_TRUE(got == expected) << first_difference(got, expected) << "\nproblem " << problem;
    }
  }
}

/// Row i of a list with all three outputs as (j, S, d, D) tuples, sorted; j and i renamed by
/// `name` (identity when empty).
using Entry = std::tuple<point_id, std::array<std::int32_t, 3>, double, std::array<double, 3>>;
std::vector<Entry> entries_of(const NeighborList& list, std::size_t i, const std::vector<point_id>& name = {}) {
  std::vector<Entry> row;
  for (auto e = list.offsets()[i]; e < list.offsets()[i + 1]; ++e) {
    const auto at = static_cast<std::size_t>(e);
    const point_id j = list.indices()[at];
    row.emplace_back(name.empty() ? j : name[static_cast<std::size_t>(j)],
                     std::array<std::int32_t, 3>{list.shifts()[3 * at], list.shifts()[3 * at + 1], list.shifts()[3 * at + 2]},
                     list.distances()[at],
                     std::array<double, 3>{list.vectors()[3 * at], list.vectors()[3 * at + 1], list.vectors()[3 * at + 2]});
  }
  std::sort(row.begin(), row.end());
  return row;
}

TEST(CellSearch, PointsInNoSpatialOrderGiveTheListOfTheSamePointsInOrder) {
  // 40,000 atoms in a triclinic cell, open along c: in cell order (searched as they are) and
  // shuffled (renumbered by cell inside the search, rows sorted again or not). The shuffled
  // list is the ordered one renamed, entry for entry with the same bits, on every CPU backend;
  // its half list keeps what the half rule keeps of its full list, by the caller's ids.
  std::mt19937_64 rng(59);
  Cell cell;
  cell.vectors = {{{30, 0, 0}, {8, 28, 0}, {-4, 3, 25}}};
  cell.pbc = {true, true, false};
  PointSet ordered(3, {});
  for (int i = 0; i < 40000; ++i) {
    const double f[3] = {(i % 40 + 0.5 * std::uniform_real_distribution<double>(0, 1)(rng)) / 40,
                         (i / 40 % 40 + 0.5 * std::uniform_real_distribution<double>(0, 1)(rng)) / 40,
                         (i / 1600 + 0.5 * std::uniform_real_distribution<double>(0, 1)(rng)) / 25};
    for (int a = 0; a < 3; ++a) ordered.xyz.push_back(f[0] * cell.vectors[0][a] + f[1] * cell.vectors[1][a] + f[2] * cell.vectors[2][a]);
  }
  std::vector<point_id> shuffle(ordered.size());  // shuffled point k is ordered point shuffle[k]
  std::iota(shuffle.begin(), shuffle.end(), 0);
  std::shuffle(shuffle.begin(), shuffle.end(), rng);
  std::vector<point_id> where(ordered.size());  // ordered point j is shuffled point where[j]
  PointSet shuffled(3, {});
  for (std::size_t k = 0; k < shuffle.size(); ++k) {
    where[static_cast<std::size_t>(shuffle[k])] = static_cast<point_id>(k);
    for (int a = 0; a < 3; ++a) shuffled.xyz.push_back(ordered.xyz[3 * static_cast<std::size_t>(shuffle[k]) + a]);
  }
  SearchOptions options;
  options.cell = cell;
  options.horizon = 2.2;
  options.outputs = {true, true, true};
  options.self_interaction = true;
  const NeighborList expected = search(ordered.view(), options);
  for (Backend backend : {Backend::serial, Backend::openmp}) {
    for (bool sorted : {true, false}) {
      options.backend = backend;
      options.sort_rows = sorted;
      options.half = false;
      const NeighborList full = search(shuffled.view(), options);
      ASSERT_EQ(full.total(), expected.total());
      for (std::size_t k = 0; k < shuffled.size(); k += 7)
        ASSERT_EQ(entries_of(full, k), entries_of(expected, static_cast<std::size_t>(shuffle[k]), where))
            << "row " << k << " on " << backend_name(backend) << (sorted ? ", sorted" : ", unsorted");
      if (sorted) {
        for (std::size_t k = 0; k < shuffled.size(); ++k) {
          const auto row = full.row(k);
          ASSERT_TRUE(std::is_sorted(row.begin(), row.end())) << "row " << k;
        }
      }
      options.half = true;
      const NeighborList half = search(shuffled.view(), options);
      for (std::size_t k = 0; k < shuffled.size(); k += 7) {
        std::vector<Entry> kept;
        for (const Entry& e : entries_of(full, k)) {
          const point_id j = std::get<0>(e);
          const auto& shift = std::get<1>(e);
          const bool positive = shift[0] > 0 || (shift[0] == 0 && (shift[1] > 0 || (shift[1] == 0 && shift[2] >= 0)));
          if (j > static_cast<point_id>(k) || (j == static_cast<point_id>(k) && positive)) kept.push_back(e);
        }
        ASSERT_EQ(entries_of(half, k), kept) << "half row " << k << " on " << backend_name(backend);
      }
    }
  }
}

TEST(CellSearch, NoPointsGiveAnEmptyListWithItsGeometry) {
  SearchOptions options;
  options.horizon = 1.0;
  options.cell = Cell::orthorhombic({2, 2, 2});
  options.outputs.distances = true;
  const PointSet none(3, {});
  EXPECT_EQ(search(none.view(), options).total(), 0);
  const NeighborList radii = search_with_radii(none.view(), {}, RadiusRule::sum, options);
  EXPECT_EQ(radii.total(), 0);
  EXPECT_TRUE(radii.outputs().distances);
}

TEST(CellSearch, OneAtomInASmallCellFindsItsImagesShellByShell) {
  // Simple cubic, a = 1, horizon 1.5: the 6 images at distance 1 and the 12 at sqrt(2) (sqrt(3)
  // = 1.73 is out); with horizon 2.1 also the 8 at sqrt(3) and the 6 at 2.
  for (Backend backend : cpu_and_gpu()) {
    SearchOptions options;
    options.backend = backend;
    options.cell = Cell::orthorhombic({1, 1, 1});
    options.outputs = {true, true, true};
    const PointSet atom(3, {0.25, 0.5, 0.75});
    options.horizon = 1.5;
    NeighborList list = search(atom.view(), options);
    ASSERT_EQ(list.total(), 18);
    int ones = 0;
    for (std::int64_t e = 0; e < list.total(); ++e) {
      EXPECT_EQ(list.indices()[e], 0);
      double norm2 = 0;
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(list.vectors()[e * 3 + a], static_cast<double>(list.shifts()[e * 3 + a]));
        norm2 += list.vectors()[e * 3 + a] * list.vectors()[e * 3 + a];
      }
      EXPECT_DOUBLE_EQ(list.distances()[e], std::sqrt(norm2));
      ones += list.distances()[e] == 1.0;
    }
    EXPECT_EQ(ones, 6);
    EXPECT_EQ(std::vector<std::int32_t>(list.shifts().begin(), list.shifts().begin() + 3),
              (std::vector<std::int32_t>{-1, -1, 0}));  // the first shift in lexicographic order
    options.horizon = 2.1;
    EXPECT_EQ(search(atom.view(), options).total(), 6 + 12 + 8 + 6);
    options.half = true;
    EXPECT_EQ(search(atom.view(), options).total(), (6 + 12 + 8 + 6) / 2);
    options.self_interaction = true;
    list = search(atom.view(), options);
    EXPECT_EQ(list.total(), 16 + 1);
  }
}

TEST(CellSearch, AnOrthorhombicCellGivesTheBoxsIds) {
  const PointSet points = random_cloud(3000, 3, 11, 10.0);
  SearchOptions box;
  box.horizon = 1.2;
  box.box = {10, 10, 10};
  SearchOptions cell = box;
  cell.box = {0, 0, 0};
  cell.cell = Cell::orthorhombic({10, 10, 10});
  for (bool half : {false, true}) {
    box.half = cell.half = half;
    const NeighborList expected = search(points.view(), box);
    const NeighborList got = search(points.view(), cell);
    EXPECT_EQ(got.offsets(), expected.offsets());
    EXPECT_EQ(got.indices(), expected.indices());
    cell.outputs.shifts = true;  // the same with shifts, and with the box as the cell
    box.outputs.shifts = true;
    EXPECT_EQ(search(points.view(), box), search(points.view(), cell));
    cell.outputs.shifts = box.outputs.shifts = false;
  }
}

TEST(CellSearch, OpenAxesIgnoreTheirVectors) {
  // A slab: periodic in a and b; whatever c says (zero, tilted) the list is the same.
  Cell slab;
  slab.vectors = {{{3, 0, 0}, {1, 2.5, 0}, {0, 0, 0}}};
  slab.pbc = {true, true, false};
  const PointSet points = random_cloud(50, 3, 7, 4.0);
  SearchOptions options;
  options.horizon = 2.5;
  options.cell = slab;
  options.outputs = {true, true, true};
  const NeighborList expected = search(points.view(), options);
  options.cell.vectors[2] = {0.5, -1, 7};
  const NeighborList tilted = search(points.view(), options), oracle = brute_force(points.view(), options);
  EXPECT_TRUE(tilted == expected) << first_difference(tilted, expected);
  EXPECT_TRUE(oracle == expected) << first_difference(oracle, expected);
}

TEST(CellSearch, GeometryThatCannotFitIsListTooLarge) {
  const PointSet points = random_cloud(2000, 3, 3, 5.0);
  SearchOptions options;
  options.horizon = 1.0;
  options.cell = Cell::orthorhombic({5, 5, 5});
  options.outputs = {true, true, true};
  const auto entries = static_cast<std::size_t>(search(points.view(), options).total());
  options.max_memory = entries * 20;  // the ids fit (4 bytes an entry), not with 44 more for S, d and D
  EXPECT_THROW(search(points.view(), options), ListTooLarge);
  options.outputs = {};
  EXPECT_EQ(search(points.view(), options).total(), static_cast<std::int64_t>(entries));
}

TEST(CellSearch, BadCellsAreClearErrors) {
  const PointSet points = random_cloud(10, 3, 1, 1.0);
  auto message = [&](const Cell& cell, const std::string& expected, SearchOptions options = {}) {
    options.horizon = 0.5;
    options.cell = cell;
    try {
      search(points.view(), options);
      ADD_FAILURE() << "no error; expected " << expected;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  Cell cell = Cell::orthorhombic({1, 1, 1});
  cell.vectors[1] = {2, 0, 0};  // parallel to a
  message(cell, "linearly dependent");
  cell = Cell::orthorhombic({1, 1, 1});
  std::swap(cell.vectors[0], cell.vectors[1]);
  message(cell, "left-handed");
  cell = Cell::orthorhombic({1, 1, 1});
  cell.vectors[2] = {0, 0, 0};
  message(cell, "vector c has zero length but its axis is periodic");
  cell = Cell::orthorhombic({1, 1, 1});
  cell.vectors[1][2] = std::nan("");
  message(cell, "vector b has a non-finite component 2");
  SearchOptions with_box;
  with_box.box = {1, 1, 1};
  message(Cell::orthorhombic({1, 1, 1}), "either a box or a cell", with_box);
  SearchOptions queries;
  queries.queries = 3;
  message(Cell::orthorhombic({1, 1, 1}), "queries", queries);
  const PointSet plane = random_cloud(10, 2, 1, 1.0);
  SearchOptions options;
  options.horizon = 0.5;
  options.cell = Cell::orthorhombic({1, 1, 1});
  EXPECT_THROW(search(plane.view(), options), Error);  // pbc on c for 2-D points
}

}  // namespace
}  // namespace horizon
