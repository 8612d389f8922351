#pragma once
// A list from search_in_batches put together, each batch checked for order and size as it comes.
#include <gtest/gtest.h>

#include <vector>

#include "horizon/batched_search.hpp"

namespace horizon::testing {

/// The batches of search_in_batches, checked for order and size as they come, put together.
inline NeighborList assemble_batches(PointView points, const SearchOptions& options, std::int64_t batch_entries) {
  Buffer<std::int64_t> offsets;
  std::vector<point_id> ids;
  std::size_t next = 0;
  RowBatchSink sink;
  sink.begin = [&](const std::int64_t* o, std::size_t rows) {
    EXPECT_EQ(rows, points.size());
    offsets = Buffer<std::int64_t>(o, o + rows + 1);
  };
  sink.rows = [&](std::size_t first, std::size_t last, const point_id* batch) {
    EXPECT_EQ(first, next);
    EXPECT_GT(last, first);
    const std::int64_t entries = offsets[last] - offsets[first];
    EXPECT_TRUE(entries <= batch_entries || last == first + 1) << entries << " entries in rows " << first << "-" << last;
    ids.insert(ids.end(), batch, batch + entries);
    next = last;
  };
  search_in_batches(points, options, batch_entries, sink);
  EXPECT_EQ(next, points.size());
  return NeighborList(std::move(offsets), Buffer<point_id>(ids.begin(), ids.end()), options.half);
}

}  // namespace horizon::testing
