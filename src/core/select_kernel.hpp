#pragma once
// The two inner loops of a copying selection (select_entries.hpp), compiled for each SIMD
// instruction set with the best one this CPU has picked at run time: marking the stored
// candidates still within a threshold (the Verlet refresh), and writing the marked ids.
#include <cstdint>

#include "horizon/metric.hpp"
#include "horizon/neighbor_list.hpp"

namespace horizon::detail {

/// Sets bit e % 64 of bits[e / 64] to whether candidate ids[e] (e < count) lies within
/// `threshold` of `point`: metric_accumulate(point - candidate) < threshold, the search's
/// arithmetic, for points of `dims` coordinates each in `xyz`. Returns how many are marked.
std::int64_t mark_within(Metric metric, int dims, const double* point, const point_id* ids, std::int64_t count,
                         const double* xyz, double threshold, std::uint64_t* bits);

/// Writes ids[e] for each e < count marked in `bits` to out, in order: `marked` ids, nothing
/// past them.
void write_marked(const point_id* ids, std::int64_t count, const std::uint64_t* bits, std::int64_t marked,
                  point_id* out);

}  // namespace horizon::detail
