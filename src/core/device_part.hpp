#pragma once
// GPU parts (horizon::DevicePart) as the multi-GPU search builds them, and the host path's copy
// of their rows straight to their places in the assembled list: no list of a part in host
// memory, read again and rewritten by the assembly (partitioned_search.cpp). Defined by the
// CUDA backend (cuda/device_part.cuh); without CUDA they throw.
#include <cstdint>
#include <span>
#include <vector>

#include "horizon/cuda.hpp"
#include "horizon/neighbor_list.hpp"
#include "horizon/points.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

/// A part's local points: its owned points and its halo in one ascending order of global id
/// (a local list's rows are then sorted in global ids too, and a half list keeps j > i
/// globally), each one's global id, and the local rows of the owned points.
struct LocalPart {
  PointView points;
  std::span<const point_id> global;
  std::span<const point_id> owned_rows;
};

/// Searches a local part on options.device and keeps the owned points' rows there, mapped to
/// global ids. Throws DeviceOutOfMemory when the local list and the owned rows do not fit.
DevicePart search_local_part(const LocalPart& part, const SearchOptions& options, SearchStats* stats);

/// A part's rows on their way to the host list: row r (point ids[r]; offsets on the host) goes
/// to indices + at[ids[r]]. `part` is null in tests that stage the rows themselves.
struct PartRows {
  const DevicePart* part;
  std::span<const std::int64_t> offsets;
  std::span<const point_id> ids;
};

/// The row offsets of a device part, copied to the host.
Buffer<std::int64_t> host_offsets(const DevicePart& part);

/// Places rows [first, last) of a part that arrived at `staged` (row r at offsets[r] -
/// offsets[first]), on all cores: compiled as C++ with OpenMP, which CUDA sources are not.
void place_rows(const PartRows& part, std::size_t first, std::size_t last, const point_id* staged,
                const std::int64_t* at, point_id* indices);

/// Copies the rows of every part to their places, every part's copy under way at once and all
/// cores placing the rows that have arrived.
void copy_part_rows(const std::vector<PartRows>& parts, const std::int64_t* at, point_id* indices);

}  // namespace horizon::detail
