#pragma once
// One part of a search over several GPUs whose list stays on its GPU until each row is copied
// straight to its place in the assembled list: no list of the part in host memory, read again
// and rewritten by the assembly (partitioned_search.cpp). Defined by the CUDA backend
// (cuda/device_part.cuh); without CUDA, search_on_device throws.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "horizon/neighbor_list.hpp"
#include "horizon/points.hpp"
#include "horizon/search.hpp"

namespace horizon::detail {

class DevicePart {
public:
  virtual ~DevicePart() = default;
  /// Row offsets of every local point, on the host.
  virtual const Buffer<std::int64_t>& offsets() const = 0;
};

/// A part's rows to copy: local row r, when keep[r], goes to indices + at[global[r]].
struct PartRows {
  const DevicePart* part;
  std::span<const std::uint8_t> keep;
  std::span<const point_id> global;
};

/// Places rows [first, last) of a part that arrived at `staged` (row r at offsets[r] -
/// offsets[first]), on all cores: compiled as C++ with OpenMP, which CUDA sources are not.
void place_rows(const PartRows& part, const std::int64_t* offsets, std::size_t first, std::size_t last,
                const point_id* staged, const std::int64_t* at, point_id* indices);

/// Copies the rows of every part to their places, every part's copy under way at once and all
/// cores placing the rows that have arrived.
void copy_part_rows(const std::vector<PartRows>& parts, const std::int64_t* at, point_id* indices);

/// The list of `local` (points ascending by global id; `global`: each one's) on
/// options.device, its ids mapped to global ids there. Rows stay sorted and a half list keeps
/// j > i by global id, since the map ascends. Throws DeviceOutOfMemory when it does not fit.
std::unique_ptr<DevicePart> search_on_device(PointView local, std::span<const point_id> global,
                                             const SearchOptions& options);

}  // namespace horizon::detail
