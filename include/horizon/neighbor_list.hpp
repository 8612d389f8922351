#pragma once
/// \file neighbor_list.hpp
/// The result: every point's family in compressed sparse rows. Row i lists the input ids of
/// i's neighbours in ascending order. In a full list j is in row i exactly when i is in row j;
/// a half list keeps each pair once, in the row of its smaller id. A search with a periodic
/// cell (cell.hpp) may list j several times in a row, once per periodic image.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "horizon/buffer.hpp"
#include "horizon/cell.hpp"
#include "horizon/points.hpp"

namespace horizon {

class NeighborList {
public:
  NeighborList() : offsets_(1, 0) {}
  NeighborList(Buffer<std::int64_t> offsets, Buffer<point_id> indices, bool half)
      : offsets_(std::move(offsets)), indices_(std::move(indices)), half_(half) {}

  /// Number of rows (points).
  std::size_t size() const { return offsets_.size() - 1; }
  /// Total number of entries (each pair counted twice in a full list).
  std::int64_t total() const { return offsets_.back(); }
  bool is_half() const { return half_; }

  /// The family of point i, sorted ascending.
  std::span<const point_id> row(std::size_t i) const {
    return {indices_.data() + offsets_[i], static_cast<std::size_t>(offsets_[i + 1] - offsets_[i])};
  }
  std::size_t row_size(std::size_t i) const {
    return static_cast<std::size_t>(offsets_[i + 1] - offsets_[i]);
  }

  /// CSR arrays: offsets has size()+1 entries, indices has total().
  const Buffer<std::int64_t>& offsets() const { return offsets_; }
  const Buffer<point_id>& indices() const { return indices_; }

  /// Per-entry geometry, when SearchOptions::outputs asked for it (else empty): for entry e,
  /// shifts()[e * dims + a], distances()[e] and vectors()[e * dims + a] (dims: the points').
  const Buffer<std::int32_t>& shifts() const { return shifts_; }
  const Buffer<double>& distances() const { return distances_; }
  const Buffer<double>& vectors() const { return vectors_; }
  /// Which of them the list carries, and the points' dimension (components per shift and vector).
  const PairOutputs& outputs() const { return outputs_; }
  int geometry_dims() const { return geometry_dims_; }
  /// Attaches the per-entry geometry of `dims`-D points: those `outputs` names, sized as above.
  void set_geometry(PairOutputs outputs, Buffer<std::int32_t> shifts, Buffer<double> distances, Buffer<double> vectors,
                    int dims) {
    outputs_ = outputs;
    shifts_ = std::move(shifts);
    distances_ = std::move(distances);
    vectors_ = std::move(vectors);
    geometry_dims_ = outputs.any() ? dims : 0;
  }

  /// Gives up the CSR arrays (the list is left empty), for filters that reuse them in place.
  std::pair<Buffer<std::int64_t>, Buffer<point_id>> release() && {
    std::pair<Buffer<std::int64_t>, Buffer<point_id>> arrays{std::move(offsets_), std::move(indices_)};
    offsets_.assign(1, 0);
    indices_.clear();
    set_geometry({}, {}, {}, {}, 0);
    return arrays;
  }

  friend bool operator==(const NeighborList&, const NeighborList&) = default;

private:
  Buffer<std::int64_t> offsets_;
  Buffer<point_id> indices_;
  bool half_ = false;
  Buffer<std::int32_t> shifts_;
  Buffer<double> distances_, vectors_;
  PairOutputs outputs_;
  int geometry_dims_ = 0;
};

}  // namespace horizon
