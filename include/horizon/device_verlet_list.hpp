#pragma once
/// \file device_verlet_list.hpp
/// The Verlet list of verlet_list.hpp for points kept on the GPU: device coordinates in, device
/// CSR out, on the caller's stream. The candidates (pairs within horizon + skin) stay on the
/// GPU; refresh() filters them with the search's arithmetic, 8-32 lanes per row. Usable (and
/// throwing) when built without CUDA.
#include <memory>

#include "horizon/cuda.hpp"

namespace horizon {

class DeviceVerletList {
public:
  /// Searches the `count` points at device `xyz` (AoS x y [z], float64) with `options` widened
  /// by `skin` > 0 on `stream` (of device options.device, which must be current), and keeps a
  /// copy of the positions and room for a refresh's work (a bit per candidate). Periodic boxes are not supported
  /// (throws).
  DeviceVerletList(const double* xyz, std::size_t count, int dims, const SearchOptions& options, double skin,
                   cuda_stream stream = nullptr);

  /// As VerletList::needs_rebuild, for device positions `xyz` of the same points; waits for
  /// the stream. Coordinates are not validated on the GPU: a NaN counts as moved.
  bool needs_rebuild(const double* xyz) const;

  /// The exact list of device positions `xyz` within the horizon, on the stream: equal to
  /// search_device(xyz, ...) while !needs_rebuild(xyz). Waits for the stream once, to size it.
  DeviceNeighborList refresh(const double* xyz) const;

  /// The pairs within horizon + skin of the positions at the build.
  const DeviceNeighborList& candidates() const { return candidates_; }

private:
  SearchOptions options_;
  double skin_ = 0;
  int dims_ = 3;
  cuda_stream stream_ = nullptr;
  DeviceNeighborList candidates_;
  std::unique_ptr<double, DeviceNeighborList::Free> built_at_;  ///< the positions at the build
  /// A refresh's row sizes, scan storage (from scan_at_) and verdicts, a bit per candidate
  /// (from marks_at_): reused by every refresh (all on stream_).
  std::unique_ptr<unsigned char, DeviceNeighborList::Free> workspace_;
  std::size_t scan_at_ = 0, marks_at_ = 0;
};

}  // namespace horizon
