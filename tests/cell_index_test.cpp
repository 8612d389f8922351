// The cell sort: the same index on any thread count, each cell's points ascending by input id;
// periodic images after the rows of their cell, named by their originals. A cell's sorted
// stencil slid from the cell before it equals the one gathered afresh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/radix_sort.hpp"
#include "core/sorted_stencil.hpp"
#include "datasets.hpp"
#include "horizon/cell_index.hpp"
#include "horizon/generate.hpp"

namespace horizon {
namespace {

void expect_same_index(const CellIndex& a, const CellIndex& b) {
  ASSERT_EQ(a.occupied_cells(), b.occupied_cells());
  const auto n = static_cast<std::ptrdiff_t>(a.point_count() + CellIndex::padding);
  EXPECT_TRUE(std::equal(a.order().begin(), a.order().begin() + n, b.order().begin()));
  for (std::size_t c = 0; c < a.occupied_cells(); ++c) {
    EXPECT_EQ(a.points_of(c).begin, b.points_of(c).begin);
    EXPECT_EQ(a.points_of(c).end, b.points_of(c).end);
  }
  for (int axis = 0; axis < 3; ++axis)
    for (std::size_t p = 0; p < a.point_count(); ++p) ASSERT_EQ(a.coords(axis)[p], b.coords(axis)[p]);
}

TEST(CellIndex, AnyThreadCountGivesTheSerialSortStableById) {
  for (const int dims : {2, 3})
    for (auto& data : testing::datasets(dims))
      for (const int k : {1, 3}) {
        SCOPED_TRACE(data.name + " " + std::to_string(dims) + "-D k " + std::to_string(k));
        const Grid grid = Grid::fit(data.points.view(), data.horizon, k);
        const CellIndex serial(data.points.view(), grid, 1);
        for (std::size_t c = 0; c < serial.occupied_cells(); ++c) {
          const auto [first, last] = serial.points_of(c);
          EXPECT_TRUE(std::is_sorted(serial.order().begin() + first, serial.order().begin() + last));
        }
        for (const int threads : {2, 3, 7}) expect_same_index(serial, CellIndex(data.points.view(), grid, threads));
      }
}

TEST(CellIndex, LargeClusteredAndFlatInputsGiveTheSerialSort) {
  // Dense grids of 9x10^4 and 2.5x10^5 cells (radix sorts of two passes), cells holding
  // thousands of points, more threads than cores; the same cells as a sparse grid.
  const PointSet clustered = clustered_cloud(200000, 3, 0.05);
  const PointSet flat = random_cloud(100000, 2);
  for (const auto& [points, horizon] : {std::pair{&clustered, 0.1}, std::pair{&flat, 0.02}}) {
    Grid grid = Grid::fit(points->view(), horizon, 1);
    ASSERT_TRUE(grid.dense);
    const CellIndex serial(points->view(), grid, 1);
    for (const int threads : {2, 5, 16}) expect_same_index(serial, CellIndex(points->view(), grid, threads));
    grid.dense = false;  // the sparse sort (a parallel merge sort) gives the same index
    for (const int threads : {1, 2, 5, 16}) expect_same_index(serial, CellIndex(points->view(), grid, threads));
  }
}

// A sparse grid (a table over every cell would be too large) finds a row of cells in a hash
// table and a run of its cells from the row's column table or by binary search: the same
// index, stencils and runs as the dense grid over the same cells.
TEST(CellIndex, SparseGridsGiveTheDenseGridsStencils) {
  auto expect_same_ranges = [](const std::vector<CellIndex::Range>& a, const std::vector<CellIndex::Range>& b, int n) {
    for (int r = 0; r < n; ++r) {
      EXPECT_EQ(a[r].begin, b[r].begin) << "range " << r;
      EXPECT_EQ(a[r].end, b[r].end) << "range " << r;
    }
  };
  int compared = 0;
  for (const int dims : {2, 3})
    for (auto& data : testing::datasets(dims))
      for (const int k : {1, 2, 3}) {
        SCOPED_TRACE(data.name + " " + std::to_string(dims) + "-D k " + std::to_string(k));
        Grid grid = Grid::fit(data.points.view(), data.horizon, k);
        if (!grid.dense) continue;
        const CellIndex dense(data.points.view(), grid, 1);
        grid.dense = false;
        const CellIndex sparse(data.points.view(), grid, 1);
        expect_same_index(dense, sparse);
        ++compared;
        const int width = 2 * k + 1, cells = dense.max_stencil_cells();
        std::vector<CellIndex::Range> a(static_cast<std::size_t>(cells)), b(a.size());
        for (std::size_t c = 0; c < dense.occupied_cells(); ++c) {
          int n = dense.stencil(c, a.data());
          ASSERT_EQ(n, sparse.stencil(c, b.data()));
          expect_same_ranges(a, b, n);
          n = dense.upper_stencil(c, a.data());
          ASSERT_EQ(n, sparse.upper_stencil(c, b.data()));
          expect_same_ranges(a, b, n);
          for (int first = -k; first <= k; ++first) {
            n = dense.stencil_columns(c, first, k - (first + k) / 2, a.data());
            ASSERT_EQ(n, sparse.stencil_columns(c, first, k - (first + k) / 2, b.data()));
            expect_same_ranges(a, b, n);
          }
          // Cell by cell, empty runs may sit anywhere: every run of a row's cells a .. b is the same.
          dense.stencil_cells(c, a.data());
          sparse.stencil_cells(c, b.data());
          for (int row = 0; row < cells / width; ++row)
            for (int first = 0; first < width; ++first)
              for (int last = first; last < width; ++last) {
                const auto& [da, db] = std::pair{a[row * width + first].begin, a[row * width + last].end};
                const auto& [sa, sb] = std::pair{b[row * width + first].begin, b[row * width + last].end};
                ASSERT_EQ(std::max<std::int64_t>(db - da, 0), std::max<std::int64_t>(sb - sa, 0))
                    << "cell " << c << " row " << row << " columns " << first << ".." << last;
                if (db > da) ASSERT_EQ(da, sa);
              }
        }
      }
  EXPECT_GT(compared, 30);
}

TEST(CellIndex, ImagesHoldNoRowAndCarryTheirOriginalsIds) {
  // Points 0..5 on a line, then images of points 1, 4 and 0 (standing anywhere), on any thread count.
  const std::vector<double> xyz = {0.1, 0, 0.5, 0, 0.9, 0, 1.3, 0, 2.2, 0, 2.6, 0, -0.4, 0, 2.95, 0, 0.05, 0};
  const PointView points(xyz.data(), 6, 2), images(xyz.data() + 12, 3, 2);
  const std::vector<point_id> image_of = {1, 4, 0};
  const Grid grid = Grid::fit(points, images, 1.0, 1);
  for (const int threads : {1, 3}) {
    const CellIndex index(points, grid, threads, Images{images, image_of});
    EXPECT_EQ(index.point_count(), 9u);
    EXPECT_EQ(index.row_count(), 6u);
    std::vector<point_id> rows, images;
    for (std::size_t c = 0; c < index.occupied_cells(); ++c) {
      const auto [first, last] = index.points_of(c);
      const auto rows_end = index.rows_of(c).end;
      for (std::int64_t p = first; p < last; ++p) {
        const point_id id = index.order()[static_cast<std::size_t>(p)];
        (p < rows_end ? rows : images).push_back(id);
        // Each slot keeps its own coordinates: an image's are not its original's.
        const auto image = std::find(image_of.begin(), image_of.end(), id) - image_of.begin();
        const std::size_t local = p < rows_end ? static_cast<std::size_t>(id) : 6 + static_cast<std::size_t>(image);
        EXPECT_EQ(index.coords(0)[static_cast<std::size_t>(p)], xyz[2 * local]);
      }
    }
    std::sort(rows.begin(), rows.end());
    std::sort(images.begin(), images.end());
    EXPECT_EQ(rows, (std::vector<point_id>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(images, (std::vector<point_id>{0, 1, 4}));
  }
}

TEST(SortedStencil, SlidingAlongXGathersWhatAFreshGatherDoes) {
  std::size_t slid = 0;  // cells whose stencil was slid from the one before (the test must reach some)
  for (const int dims : {2, 3})
    for (auto& data : testing::datasets(dims))
      for (const int k : {1, 2, 3})
        for (const int skip : {0, 3}) {  // 3: every third cell not gathered, as small stencils are not
          SCOPED_TRACE(data.name + " " + std::to_string(dims) + "-D k " + std::to_string(k) + " skip " +
                       std::to_string(skip));
          const CellIndex index(data.points.view(), Grid::fit(data.points.view(), data.horizon, k), 1);
          detail::SortedStencil sliding;
          std::array<std::int64_t, 3> last{0, 0, -2};  // the cell gathered last
          for (std::size_t c = 0; c < index.occupied_cells(); ++c) {
            if (skip && c % skip == 0) continue;
            const auto& cell = index.cell_coord(c);
            slid += cell[0] == last[0] && cell[1] == last[1] && cell[2] == last[2] + 1;
            last = cell;
            sliding.gather(index, c);
            detail::SortedStencil fresh;
            fresh.gather(index, c);
            ASSERT_EQ(sliding.size(), fresh.size());
            const auto n = static_cast<std::size_t>(fresh.size());
            EXPECT_TRUE(std::equal(fresh.ids(), fresh.ids() + n + CellIndex::padding, sliding.ids()));
            for (int axis = 0; axis < 3; ++axis) {
              EXPECT_TRUE(std::equal(fresh.coords(axis), fresh.coords(axis) + n, sliding.coords(axis)));
              for (std::size_t s = n; s < n + CellIndex::padding; ++s) EXPECT_TRUE(std::isnan(sliding.coords(axis)[s]));
            }
          }
        }
  EXPECT_GT(slid, 1000u);
}

TEST(RadixSort, SortsByTheHighWordKeepingTheLowWordsOrder) {
  // 23 cell bits (three passes of 8), many equal cells, on thread counts that split unevenly.
  std::mt19937_64 rng(5);
  ScratchBuffer<std::uint64_t> keys(100003);
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = (rng() % (rng() % 2 ? 7 : 1u << 23)) << 32 | i;
  std::vector<std::uint64_t> expected(keys.begin(), keys.end());
  std::stable_sort(expected.begin(), expected.end(), [](auto a, auto b) { return a >> 32 < b >> 32; });
  for (const int threads : {1, 2, 5}) {
    ScratchBuffer<std::uint64_t> sorted = keys;
    detail::radix_sort_high_word(sorted, 23, threads);
    EXPECT_TRUE(std::equal(sorted.begin(), sorted.end(), expected.begin())) << threads << " threads";
  }
}

}  // namespace
}  // namespace horizon
