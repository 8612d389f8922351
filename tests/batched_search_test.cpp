// Lists built in batches of rows: the batches, put together, are the list search() builds, for
// every dataset, metric, k, full/half, sorted/unsorted, CPU backend and batch size; and the files
// write_neighbor_list_in_batches writes are those write_neighbor_list writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

#include "assemble_batches.hpp"
#include "core/row_batches.hpp"
#include "datasets.hpp"
#include "horizon/batched_search.hpp"
#include "horizon/error.hpp"
#include "horizon/io.hpp"

namespace horizon {
namespace {

// The cut the CPU's batched paths share (lists larger than memory, the transpose's waves):
// each batch is the longest run of rows that fits, or one longer row alone, and the batches
// cover every row once, empty rows too.
TEST(BatchedSearch, EachBatchIsTheLongestRunOfRowsThatFits) {
  std::mt19937 random(3);
  for (std::int64_t entries : {0, 1, 7, 50, 1000}) {
    std::vector<std::int64_t> offsets{0};
    for (int r = 0; r < 2000; ++r) offsets.push_back(offsets.back() + (random() % 4 == 0 ? 0 : random() % 120));
    const std::size_t n = offsets.size() - 1;
    for (std::size_t first = 0; first < n;) {
      const std::size_t last = detail::batch_end(offsets.data(), n, first, entries);
      ASSERT_GT(last, first);
      ASSERT_LE(last, n);
      if (last > first + 1) ASSERT_LE(offsets[last] - offsets[first], entries);
      if (last < n) ASSERT_GT(offsets[last + 1] - offsets[first], entries) << "row " << last << " fits too";
      first = last;
    }
  }
}

TEST(BatchedSearch, BatchesMakeTheSameListAsOneSearch) {
  for (int dims : {2, 3})
    for (const auto& data : testing::datasets(dims))
      for (Metric metric : {Metric::euclidean, Metric::manhattan, Metric::chebyshev})
        for (int k : {1, 2})
          for (bool half : {false, true})
            for (bool sorted : {true, false})
              for (Backend backend : {Backend::serial, Backend::openmp}) {
                SearchOptions options = testing::options_for(data, metric, k, half, backend);
                options.sort_rows = sorted;
                options.threads = 3;
                const NeighborList whole = search(data.points.view(), options);
                // Batches of one row each cost a pass over the grid per row: one backend is enough.
                for (std::int64_t batch : {std::int64_t{25}, std::int64_t{5000}}) {
                  if (batch < 5000 && backend == Backend::openmp) continue;
                  const NeighborList parts = testing::assemble_batches(data.points.view(), options, batch);
                  ASSERT_EQ(parts.offsets(), whole.offsets()) << data.name << " dims " << dims << " batch " << batch;
                  ASSERT_EQ(parts.indices(), whole.indices()) << data.name << " dims " << dims << " batch " << batch;
                }
              }
}

TEST(BatchedSearch, QueriesAndRefusals) {
  const PointSet points = random_cloud(800, 3, 4);
  SearchOptions options;
  options.horizon = 1.5;
  options.queries = 300;
  const NeighborList parts = testing::assemble_batches(points.view(), options, 50);
  const NeighborList whole = search(points.view(), options);
  EXPECT_EQ(parts.offsets(), whole.offsets());
  EXPECT_EQ(parts.indices(), whole.indices());

  RowBatchSink ignore{[](const std::int64_t*, std::size_t) {}, [](std::size_t, std::size_t, const point_id*) {}};
  SearchOptions cuda = options;
  cuda.backend = Backend::cuda;
  EXPECT_THROW(search_in_batches(points.view(), cuda, 50, ignore), Error);
  SearchOptions periodic = options;
  periodic.box = {10, 10, 10};
  EXPECT_THROW(search_in_batches(points.view(), periodic, 50, ignore), Error);
}

std::string bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(BatchedSearch, FilesEqualThoseOfTheWholeList) {
  const auto directory = std::filesystem::temp_directory_path() / "horizon_batched_files";
  std::filesystem::create_directories(directory);
  const PointSet points = lattice(12);
  SearchOptions options;
  options.horizon = 3.015 * 10.0 / 12;
  for (bool half : {false, true}) {
    options.half = half;
    const std::string whole = (directory / "whole").string(), parts = (directory / "parts").string();
    write_neighbor_list(whole, search(points.view(), options), ListFormat::npy);
    EXPECT_EQ(write_neighbor_list_in_batches(parts, points.view(), options, 1000), lattice_entries(12, 3, 3.015) / (half ? 2 : 1));
    EXPECT_EQ(bytes_of(parts + ".offsets.npy"), bytes_of(whole + ".offsets.npy"));
    EXPECT_EQ(bytes_of(parts + ".indices.npy"), bytes_of(whole + ".indices.npy"));
  }
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace horizon
