#pragma once
// The transpose of a square list in CSR form (the scatter and max radius rules: row j holds
// every i whose gather row holds j).
#include <cstdint>

#include "horizon/buffer.hpp"
#include "horizon/neighbor_list.hpp"

namespace horizon::detail {

/// Rows 0 .. n-1 of `offsets` / `ids` (every id in [0, n)) transposed: row j of the result
/// holds every i whose row holds j, ascending. On `threads` threads; the entries are bucketed
/// in waves of at most `wave_entries` (the scratch holds 8 bytes per entry of a wave).
void transpose_rows(const std::int64_t* offsets, const point_id* ids, std::int64_t n, int threads,
                    Buffer<std::int64_t>& out_offsets, Buffer<point_id>& out_ids,
                    std::int64_t wave_entries = std::int64_t{1} << 24);

}  // namespace horizon::detail
