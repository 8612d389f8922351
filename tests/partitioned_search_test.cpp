// The one-process multi-device driver: the partition, the halos and the assembly in input order,
// with CPU backends standing in for the GPUs (the same code path runs each part), then on the
// GPU when there is one (several parts on one GPU exercise the threads and streams as well).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#if defined(HORIZON_WITH_CUDA)
#include <cuda_runtime.h>
#endif

#include "core/device_part.hpp"
#include "core/part_lists.hpp"
#include "core/partitioned_search.hpp"
#include "datasets.hpp"
#include "same_families.hpp"
#include "horizon/cuda.hpp"
#include "horizon/decomposition.hpp"
#include "horizon/grid.hpp"
#include "horizon/parts.hpp"
#include "horizon/search.hpp"

namespace horizon::testing {
namespace {

TEST(PartitionedSearch, AnyPartCountGivesTheSerialList) {
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims))
      for (Metric metric : {Metric::euclidean, Metric::chebyshev})
        for (bool half : {false, true})
          for (int parts : {1, 2, 3, 5}) {
            const SearchOptions options = options_for(data, metric, 1, half);
            std::vector<SearchOptions> per_part(static_cast<std::size_t>(parts), options);
            per_part.back().backend = Backend::openmp;
            SearchStats stats;
            const NeighborList list = detail::search_parts(data.points.view(), options, per_part, stats);
            ASSERT_EQ(list, search(data.points.view(), options))
                << data.name << " dims " << dims << " half " << half << " parts " << parts;
            ASSERT_EQ(stats.parts.size(), static_cast<std::size_t>(parts));
            std::size_t owned = 0;
            std::int64_t entries = 0;
            for (const PartStats& part : stats.parts) {
              owned += part.owned;
              entries += part.entries;
            }
            EXPECT_EQ(owned, data.points.size());
            EXPECT_EQ(entries, list.total());
          }
}

/// The list whose row ids[r] is rows.row(r) for every part: each point's row from the part
/// that owns it (a point owned twice or never fails).
template <class Part, class Rows>
NeighborList assembled(const std::vector<Part>& parts, std::size_t n, bool half, Rows rows_of) {
  std::vector<std::vector<point_id>> rows(n);
  std::vector<int> owners(n, 0);
  for (const Part& part : parts) {
    const NeighborList rows_of_part = rows_of(part);
    EXPECT_EQ(rows_of_part.size(), part.ids.size());
    for (std::size_t r = 0; r < part.ids.size(); ++r) {
      const auto row = rows_of_part.row(r);
      rows[static_cast<std::size_t>(part.ids[r])].assign(row.begin(), row.end());
      ++owners[static_cast<std::size_t>(part.ids[r])];
    }
  }
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(owners[i], 1) << "point " << i;
  Buffer<std::int64_t> offsets(n + 1, 0);
  Buffer<point_id> indices;
  for (std::size_t i = 0; i < n; ++i) {
    indices.insert(indices.end(), rows[i].begin(), rows[i].end());
    offsets[i + 1] = static_cast<std::int64_t>(indices.size());
  }
  return NeighborList(std::move(offsets), std::move(indices), half);
}

// The public parts on the CPU (the stand-in for GPU parts): every point owned once, its halo
// disjoint from it, and the union of the parts' rows the one list.
TEST(PartitionedSearch, PartsOnTheCpuGiveTheSerialList) {
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims))
      for (bool half : {false, true})
        for (int count : {1, 2, 3, 5}) {
          const SearchOptions options = options_for(data, Metric::euclidean, 1, half);
          const std::vector<OwnedPart> parts = search_in_parts(data.points.view(), count, options);
          ASSERT_EQ(parts.size(), static_cast<std::size_t>(count));
          const NeighborList list = assembled(parts, data.points.size(), half, [](const OwnedPart& p) { return p.rows; });
          ASSERT_EQ(list, search(data.points.view(), options)) << data.name << " dims " << dims << " half " << half
                                                                << " parts " << count;
          const std::vector<PointPart> cut = cut_into_parts(data.points.view(), count, options);
          for (int p = 0; p < count; ++p) {
            EXPECT_EQ(cut[p].owned, parts[p].ids);
            EXPECT_EQ(cut[p].halo.size(), parts[p].halo);
            std::vector<point_id> both;
            std::set_intersection(cut[p].owned.begin(), cut[p].owned.end(), cut[p].halo.begin(), cut[p].halo.end(),
                                  std::back_inserter(both));
            EXPECT_TRUE(both.empty());
          }
        }
}

// The walk down the cuts finds the owner and exactly the boxes every box's own test finds.
TEST(PartitionedSearch, OwnerAndNearRanksMatchEveryBoxTested) {
  for (int dims : {2, 3})
    for (int ranks : {1, 2, 3, 7, 16, 64}) {
      const PointSet points = clustered_cloud(20000, 4, 0.8, dims, static_cast<std::uint64_t>(ranks));
      const Bounds box = bounds_of(points.view(), 1);
      for (const Decomposition& d : {Decomposition::rcb(box, points.view(), ranks), Decomposition::brick(box, dims, ranks)})
        for (double reach : {0.05, 0.4, 3.0})
          for (std::size_t i = 0; i < points.size(); ++i) {
            double x[3] = {0, 0, 0};
            for (int a = 0; a < dims; ++a) x[a] = points.view()(i, a);
            std::uint64_t near = 0, expected = 0;
            const int owner = d.owner_and_near(x, reach, near);
            ASSERT_EQ(owner, d.owner(x));
            for (int r = 0; r < ranks; ++r)
              if (r != owner && d.box(r).near(x, dims, reach)) expected |= std::uint64_t{1} << r;
            ASSERT_EQ(near, expected) << "point " << i << " ranks " << ranks << " reach " << reach;
          }
    }
}

// A GPU part's lists (its own points and its halo in one ascending order, and where its own
// ones lie in it) hold the same points as the host path's.
TEST(PartitionedSearch, GpuPartListsHoldTheHostPathsPoints) {
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims))
      for (int count : {1, 2, 3, 5, 8}) {
        const detail::PartCut cut(data.points.view(), count, data.horizon);
        const std::vector<detail::PartLists> host = cut.lists(data.points.view(), false);
        const std::vector<detail::PartLists> gpu = cut.lists(data.points.view(), true);
        std::vector<int> owners(data.points.size(), 0);
        for (int p = 0; p < count; ++p) {
          ASSERT_EQ(gpu[p].owned, host[p].owned) << data.name << " part " << p;
          ASSERT_EQ(gpu[p].halo_count, host[p].halo.size());
          std::vector<point_id> both;
          std::merge(host[p].owned.begin(), host[p].owned.end(), host[p].halo.begin(), host[p].halo.end(),
                     std::back_inserter(both));
          ASSERT_TRUE(std::equal(both.begin(), both.end(), gpu[p].global.begin(), gpu[p].global.end()));
          ASSERT_EQ(gpu[p].owned_rows.size(), gpu[p].owned.size());
          for (std::size_t k = 0; k < gpu[p].owned.size(); ++k) {
            ASSERT_EQ(gpu[p].global[gpu[p].owned_rows[k]], gpu[p].owned[k]);
            ++owners[static_cast<std::size_t>(gpu[p].owned[k])];
          }
        }
        for (int owned : owners) ASSERT_EQ(owned, 1);
      }
}

TEST(PartitionedSearch, PartsRefuseWhatTheyCannotCut) {
  const PointSet points = random_cloud(100, 3, 1);
  SearchOptions options;
  options.horizon = 0.2;
  EXPECT_THROW(cut_into_parts(points.view(), 0, options), Error);
  EXPECT_THROW(cut_into_parts(points.view(), 65, options), Error);
  options.box = {1, 1, 1};
  EXPECT_THROW(search_in_parts(points.view(), 2, options), Error);
  options.box = {0, 0, 0};
  options.horizon = -1;
  EXPECT_THROW(cut_into_parts(points.view(), 2, options), Error);
}

TEST(PartitionedSearch, PartsHoldEqualPointCounts) {
  const PointSet points = clustered_cloud(200000, 5, 0.5, 3, 4);
  SearchOptions options;
  options.horizon = 0.1;
  options.backend = Backend::openmp;
  SearchStats stats;
  detail::search_parts(points.view(), options, std::vector<SearchOptions>(4, options), stats);
  for (const PartStats& part : stats.parts) EXPECT_NEAR(part.owned, 50000.0, 1000.0);
  // A lattice larger than the cut's sample: its planes of 1 % each, the cut on the middle one.
  const PointSet grid = lattice(100);
  options.horizon = 0.15;
  for (const PointPart& part : cut_into_parts(grid.view(), 2, options)) EXPECT_EQ(part.owned.size(), 500000u);
}

TEST(PartitionedSearch, UnsortedRowsHoldTheSameFamilies) {
  const PointSet points = random_cloud(5000, 3, 8);
  SearchOptions options;
  options.horizon = 0.9;
  options.backend = Backend::serial;
  options.sort_rows = false;
  SearchStats stats;
  const NeighborList unsorted = detail::search_parts(points.view(), options, std::vector<SearchOptions>(3, options), stats);
  options.sort_rows = true;
  expect_same_families(unsorted, search(points.view(), options));
}

// The GPU parts' host side, without a GPU: each part's rows land at their places whether they
// come alone or in runs of consecutive places (long runs are streamed), in chunks of any size.
TEST(PartitionedSearch, PlacedRowsLandAtTheirPlaces) {
  constexpr std::size_t n = 30000;
  std::mt19937 random(7);
  std::vector<int> owner(n), length(n);
  for (std::size_t g = 0; g < n;) {  // runs of 1 to 3000 rows per part
    const std::size_t run = std::min<std::size_t>(n - g, 1 + random() % 3000);
    const int p = static_cast<int>(random() % 2);
    for (std::size_t k = 0; k < run; ++k) owner[g + k] = p;
    g += run;
  }
  for (std::size_t g = 0; g < n; ++g) length[g] = g % 997 == 0 ? 6000 : static_cast<int>(random() % 60);
  std::vector<std::int64_t> at(n + 1, 0);
  for (std::size_t g = 0; g < n; ++g) at[g + 1] = at[g] + length[g];
  auto id = [](std::size_t g, int k) { return static_cast<point_id>(g * 7 + static_cast<std::size_t>(k)); };
  std::vector<point_id> indices(static_cast<std::size_t>(at[n]), -1);
  for (int p = 0; p < 2; ++p) {
    std::vector<point_id> ids, staged;
    std::vector<std::int64_t> offsets{0};
    for (std::size_t g = 0; g < n; ++g) {
      if (owner[g] != p) continue;
      ids.push_back(static_cast<point_id>(g));
      for (int k = 0; k < length[g]; ++k) staged.push_back(id(g, k));
      offsets.push_back(static_cast<std::int64_t>(staged.size()));
    }
    const detail::PartRows part{nullptr, offsets, ids};
    for (std::size_t first = 0; first < ids.size();) {  // chunks of 1 to 5000 rows
      const std::size_t last = std::min(ids.size(), first + 1 + random() % 5000);
      detail::place_rows(part, first, last, staged.data() + offsets[first], at.data(), indices.data());
      first = last;
    }
  }
  for (std::size_t g = 0; g < n; ++g)
    for (int k = 0; k < length[g]; ++k)
      ASSERT_EQ(indices[static_cast<std::size_t>(at[g]) + static_cast<std::size_t>(k)], id(g, k)) << "row " << g;
}

bool gpu_or_skip() {
  if (backend_available(Backend::cuda)) return true;
  const char* required = std::getenv("HORIZON_REQUIRE_GPU");
  if (required && std::string(required) == "1") ADD_FAILURE() << "HORIZON_REQUIRE_GPU=1 but no usable GPU";
  return false;
}

// GPU parts keep their lists on the GPU and copy each row to its place; with too little GPU
// memory for a part's list (gpu_max_memory) every part takes the host path instead.
TEST(PartitionedSearch, GpuPartsGiveTheSerialList) {
  if (!gpu_or_skip()) GTEST_SKIP() << "no usable GPU";
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims))
      for (bool half : {false, true})
        for (int parts : {2, 3})
          for (std::size_t gpu_memory : {std::size_t{0}, std::size_t{1} << 20}) {
            SearchOptions options = options_for(data, Metric::euclidean, 1, half);
            options.backend = Backend::cuda;
            options.gpu_max_memory = gpu_memory;
            SearchStats stats;
            const NeighborList list =
                detail::search_parts(data.points.view(), options, std::vector<SearchOptions>(parts, options), stats);
            SearchOptions serial = options;
            serial.backend = Backend::serial;
            ASSERT_EQ(list, search(data.points.view(), serial)) << data.name << " dims " << dims << " half " << half
                                                                  << " parts " << parts << " gpu memory " << gpu_memory;
            std::int64_t entries = 0;
            for (const PartStats& part : stats.parts) entries += part.entries;
            EXPECT_EQ(entries, list.total());
          }
}

// Parts left on their GPUs (three on one GPU): the union of their rows, brought to the host, is
// the one-GPU list; the ids on the GPU are the ids on the host; one part alone gives the same rows.
TEST(PartitionedSearch, DevicePartsGiveTheOneGpuList) {
  if (!gpu_or_skip()) GTEST_SKIP() << "no usable GPU";
  for (int dims : {2, 3})
    for (const Dataset& data : datasets(dims))
      for (bool half : {false, true}) {
        SearchOptions options = options_for(data, Metric::euclidean, 1, half, Backend::cuda);
        const NeighborList one = search(data.points.view(), options);
        options.devices = {0, 0, 0};
        SearchStats stats;
        const std::vector<DevicePart> parts = search_device_parts(data.points.view(), options, &stats);
        ASSERT_EQ(parts.size(), 3u);
        const NeighborList list = assembled(parts, data.points.size(), half, [&](const DevicePart& p) {
          return p.rows.to_host(half);
        });
        ASSERT_EQ(list, one) << data.name << " dims " << dims << " half " << half;
        const std::vector<PointPart> cut = cut_into_parts(data.points.view(), 3, options);
        for (std::size_t p = 0; p < parts.size(); ++p) {
#if defined(HORIZON_WITH_CUDA)
          std::vector<point_id> ids(parts[p].ids.size());
          ASSERT_EQ(cudaMemcpy(ids.data(), parts[p].device_ids.get(), ids.size() * sizeof(point_id),
                               cudaMemcpyDeviceToHost), cudaSuccess);
          EXPECT_EQ(ids, parts[p].ids);
#endif
          EXPECT_EQ(parts[p].halo, cut[p].halo.size());
          EXPECT_EQ(stats.parts[p].entries, parts[p].rows.total());
          const DevicePart alone = search_device_part(data.points.view(), cut[p], options);
          EXPECT_EQ(alone.ids, parts[p].ids);
          EXPECT_EQ(alone.rows.to_host(half), parts[p].rows.to_host(half));
        }
      }
}

TEST(PartitionedSearch, SeveralDevicesThroughSearchOptions) {
  if (!gpu_or_skip()) GTEST_SKIP() << "no usable GPU";
  const PointSet points = clustered_cloud(300000, 20, 0.6, 3, 9);
  SearchOptions options;
  options.horizon = 0.12;
  options.backend = Backend::cuda;
  options.devices = {0, 0, 0};  // three parts, three threads, on the one GPU there surely is
  SearchStats stats;
  const NeighborList list = search(points.view(), options, &stats);
  SearchOptions serial = options;
  serial.backend = Backend::serial;
  serial.devices.clear();
  EXPECT_EQ(list, search(points.view(), serial));
  EXPECT_EQ(stats.parts.size(), 3u);
  options.sort_rows = false;
  expect_same_families(search(points.view(), options), list);
}

}  // namespace
}  // namespace horizon::testing
