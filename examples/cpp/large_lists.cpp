// A list larger than memory: handed over in batches of whole rows, one batch held at a time.
#include <cstdio>
#include <vector>

#include <horizon/batched_search.hpp>
#include <horizon/generate.hpp>

int main() {
  horizon::PointSet points = horizon::lattice(30);
  horizon::SearchOptions options;
  options.horizon = 3.015 * 10.0 / 30;
  std::vector<std::int64_t> offsets;  // every row's offset comes first, from the count pass
  long long received = 0, batches = 0;
  horizon::RowBatchSink sink;
  sink.begin = [&](const std::int64_t* row_offsets, std::size_t n) { offsets.assign(row_offsets, row_offsets + n + 1); };
  sink.rows = [&](std::size_t first, std::size_t last, const horizon::point_id* ids) {
    received += offsets[last] - offsets[first];  // rows [first, last) are ids[0 ...]: write them out
    batches += ids != nullptr;
  };
  horizon::search_in_batches(points.view(), options, /*batch_entries=*/200000, sink);
  std::printf("%lld entries in %lld batches\n", received, batches);
  return received == offsets.back() && batches > 1 ? 0 : 1;
}
