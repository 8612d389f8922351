// The one-process multi-device driver: the partition, the halos and the assembly in input order,
// with CPU backends standing in for the GPUs (the same code path runs each part), then on the
// GPU when there is one (several parts on one GPU exercise the threads and streams as well).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "core/partitioned_search.hpp"
#include "datasets.hpp"
#include "same_families.hpp"
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

TEST(PartitionedSearch, PartsHoldEqualPointCounts) {
  const PointSet points = clustered_cloud(200000, 5, 0.5, 3, 4);
  SearchOptions options;
  options.horizon = 0.1;
  options.backend = Backend::openmp;
  SearchStats stats;
  detail::search_parts(points.view(), options, std::vector<SearchOptions>(4, options), stats);
  for (const PartStats& part : stats.parts) EXPECT_NEAR(part.owned, 50000.0, 1000.0);
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
