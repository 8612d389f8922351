#pragma once
// What builds and edits DeviceNeighborLists besides search_device: the search of a GPU part
// (its points named by their global ids, rows for its own points only; device_part.cuh) and
// the cell search on the GPU (cell_search.cu), whose lists carry shifts, distances and vectors.
#include <cstdint>

#include "horizon/cuda.hpp"

namespace horizon::detail {

/// How a GPU part names its points (device memory): names[i] is local point i's global id, all
/// below `bound` and ascending with i (so rows stay sorted and half lists keep j > i); only the
/// points with own[i] != 0 get families.
struct PartNaming {
  const point_id* names;
  std::int64_t bound;
  const std::uint8_t* own;
};

struct DeviceListAccess {
  static DeviceNeighborList search(const double* xyz, std::size_t count, int dims, const SearchOptions& options,
                                   cuda_stream stream, SearchStats* stats, const PartNaming* naming);
  /// A periodic cell of any shape, per-entry outputs or self_interaction (cell_search.cu).
  static DeviceNeighborList search_cell(const double* xyz, std::size_t count, int dims, const SearchOptions& options,
                                        cuda_stream stream, SearchStats* stats);
  static point_id* release_indices(DeviceNeighborList& list) { return list.indices_.release(); }
  static void set(DeviceNeighborList& list, std::int64_t* offsets, point_id* indices, std::size_t rows,
                  std::int64_t total, cuda_stream stream) {
    const DeviceNeighborList::Free free{stream};
    list.offsets_ = {offsets, free};
    list.indices_ = {indices, free};
    list.points_ = rows;
    list.total_ = total;
    list.stream_ = stream;
  }
  /// The per-entry outputs beside the list (each null unless asked for), freed on its stream.
  static void set_geometry(DeviceNeighborList& list, PairOutputs outputs, int dims, std::int32_t* shifts,
                           double* distances, double* vectors) {
    const DeviceNeighborList::Free free{list.stream_};
    list.outputs_ = outputs;
    list.dims_ = dims;
    list.shifts_ = {shifts, free};
    list.distances_ = {distances, free};
    list.vectors_ = {vectors, free};
  }
};

}  // namespace horizon::detail
