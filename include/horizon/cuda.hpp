#pragma once
/// \file cuda.hpp
/// The CUDA backend's device-resident entry point, for solvers that keep their points on the
/// GPU: device coordinates in, device CSR out, on the caller's stream, no host round trip.
/// This header needs no CUDA headers; it is usable (and throws) when built without CUDA.
#include <cstdint>
#include <memory>
#include <vector>

#include "horizon/error.hpp"
#include "horizon/parts.hpp"
#include "horizon/search.hpp"

struct CUstream_st;

namespace horizon {

namespace detail {
struct DeviceListAccess;
}

/// The same type as cudaStream_t; nullptr is the default stream.
using cuda_stream = CUstream_st*;

/// Thrown when the list does not fit in GPU memory; says how much it needs.
class DeviceOutOfMemory : public Error {
public:
  DeviceOutOfMemory(const std::string& what, std::size_t needed, std::size_t available)
      : Error(what), bytes_needed(needed), bytes_available(available) {}
  std::size_t bytes_needed, bytes_available;
};

/// A neighbour list in GPU memory (CSR as in NeighborList), with the per-entry outputs asked
/// for by SearchOptions::outputs beside it. Its memory comes from horizon's pool on the device
/// and goes back to it, ordered on the stream the list was built on, when the object is
/// destroyed: keep that stream alive as long as the list.
class DeviceNeighborList {
public:
  DeviceNeighborList() = default;
  std::size_t size() const { return points_; }
  std::int64_t total() const { return total_; }
  const std::int64_t* offsets() const { return offsets_.get(); }  ///< size()+1 entries
  const point_id* indices() const { return indices_.get(); }      ///< total() entries
  /// The outputs the list carries (none unless asked for) and the points' dimension.
  PairOutputs outputs() const { return outputs_; }
  int dims() const { return dims_; }
  const std::int32_t* shifts() const { return shifts_.get(); }  ///< dims() per entry, or null
  const double* distances() const { return distances_.get(); }  ///< one per entry, or null
  const double* vectors() const { return vectors_.get(); }      ///< dims() per entry, or null
  cuda_stream stream() const { return stream_; }                 ///< the stream it was built on
  /// Copies the list, and its outputs, to the host (on the stream it was built on).
  NeighborList to_host(bool half) const;

  /// Frees device memory of horizon's pool, ordered on `stream`.
  struct Free {
    cuda_stream stream;  // value-initialised (null) by unique_ptr's default constructor
    void operator()(void* pointer) const;
  };

private:
  friend DeviceNeighborList search_device(const double*, std::size_t, int, const SearchOptions&,
                                          cuda_stream, SearchStats*);
  friend class DeviceVerletList;
  friend struct detail::DeviceListAccess;
  std::unique_ptr<std::int64_t, Free> offsets_;
  std::unique_ptr<point_id, Free> indices_;
  PairOutputs outputs_;
  int dims_ = 3;
  std::unique_ptr<std::int32_t, Free> shifts_;
  std::unique_ptr<double, Free> distances_, vectors_;
  cuda_stream stream_ = nullptr;
  std::size_t points_ = 0;
  std::int64_t total_ = 0;
};

/// The neighbour list of `count` points whose AoS coordinates (x y [z], float64) are in GPU
/// memory at `xyz`, computed on `stream` (of device options.device, which must be current).
/// A periodic options.box is honoured as by search() (points checked against it on the GPU);
/// so are a periodic options.cell of any shape, options.outputs (shifts, distances, vectors on
/// the GPU beside the list) and options.self_interaction, as search() does them (the guide
/// *Atomistic systems*). Throws DeviceOutOfMemory, naming the bytes needed, when the list does
/// not fit.
DeviceNeighborList search_device(const double* xyz, std::size_t count, int dims,
                                 const SearchOptions& options, cuda_stream stream = nullptr,
                                 SearchStats* stats = nullptr);

/// One GPU's part of a search over several GPUs: the rows of the points it owns, in global ids,
/// on its GPU (what OwnedRows is for an MPI rank). Ready when returned; its memory goes back to
/// horizon's pool on its device when it is destroyed.
struct DevicePart {
  int device = 0;
  std::size_t halo = 0;       ///< points within the horizon of its box, searched as references only
  std::vector<point_id> ids;  ///< the global id of each row, ascending
  std::unique_ptr<point_id, DeviceNeighborList::Free> device_ids;  ///< `ids`, on its GPU
  /// Row r: the neighbours of point ids[r], as global ids, sorted when options.sort_rows; a half
  /// list keeps j > i by global id. The union of all parts' rows is search()'s list.
  DeviceNeighborList rows;
};

/// `points` (on the host) cut into one part per entry of options.devices (empty: options.device
/// alone; a GPU may be named more than once) as cut_into_parts does, each part searched with its
/// halo on its GPU, all at once, its rows left there. stats (optional) gets each part's points,
/// entries and seconds. Throws DeviceOutOfMemory when a part's list does not fit on its GPU.
std::vector<DevicePart> search_device_parts(PointView points, const SearchOptions& options,
                                            SearchStats* stats = nullptr);

/// One part of `points` (from cut_into_parts) searched on options.device, its rows left there.
/// stats (optional): host_to_device_seconds (gathering and uploading the part's points) and
/// kernel_seconds (the search and the rows' move to global ids).
DevicePart search_device_part(PointView points, const PointPart& part, const SearchOptions& options,
                              SearchStats* stats = nullptr);

/// horizon keeps the GPU memory of finished searches in a per-device pool, so that repeated
/// searches allocate nothing; this returns the unused part to the driver (after waiting for
/// the device). Call it when other code needs that memory.
void cuda_release_cached_memory(int device = 0);

/// Makes the device that holds `pointer` (device memory) current and returns its number; throws
/// horizon::Error naming the pointer when it is not CUDA device memory.
int cuda_use_device_of(const void* pointer);

/// Number of CUDA devices visible (0 without CUDA or a driver).
int cuda_device_count();

/// Name of a CUDA device, or "" when there is none.
std::string cuda_device_name(int device);

}  // namespace horizon
