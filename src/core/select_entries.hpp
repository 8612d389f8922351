#pragma once
// A sub-list: the entries of a list that pass a test, rows kept in order. Shared by the bond
// filters and the Verlet list's refresh.
#include <cstring>

#include "parallel_scan.hpp"
#include "horizon/neighbor_list.hpp"

namespace horizon::detail {

/// The entries j of each row i with keep(i, j); `whole(i)` true keeps row i without tests. One
/// pass of tests writes the kept entries at the original offsets, then rows move down to theirs.
template <class Whole, class Keep>
NeighborList select_entries(const NeighborList& list, Whole whole, Keep keep, int threads) {
  const auto n = static_cast<std::int64_t>(list.size());
  const std::int64_t* from = list.offsets().data();
  Buffer<point_id> kept(static_cast<std::size_t>(list.total()));
  Buffer<std::int64_t> offsets(list.size() + 1);
  offsets[0] = 0;
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto row = list.row(static_cast<std::size_t>(i));
    point_id* out = kept.data() + from[i];
    if (whole(static_cast<std::size_t>(i))) {
      if (!row.empty()) std::memcpy(out, row.data(), row.size() * sizeof(point_id));
      offsets[i + 1] = static_cast<std::int64_t>(row.size());
      continue;
    }
    std::int64_t count = 0;
    for (point_id j : row)
      if (keep(static_cast<std::size_t>(i), j)) out[count++] = j;
    offsets[i + 1] = count;
  }
  inclusive_scan(offsets.data(), offsets.size(), threads);
  if (offsets.back() == list.total()) return NeighborList(std::move(offsets), std::move(kept), list.is_half());
  Buffer<point_id> indices(static_cast<std::size_t>(offsets.back()));
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i)
    if (offsets[i + 1] > offsets[i])
      std::memcpy(indices.data() + offsets[i], kept.data() + from[i],
                  static_cast<std::size_t>(offsets[i + 1] - offsets[i]) * sizeof(point_id));
  return NeighborList(std::move(offsets), std::move(indices), list.is_half());
}

}  // namespace horizon::detail
