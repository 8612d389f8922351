#pragma once
/// \file points.hpp
/// Points as the caller stores them: a zero-copy view over AoS coordinates (x y [z] per point),
/// float64 or float32, and an owning PointSet for points read from files or generated.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace horizon {

/// Ids of points (and neighbours) are 32-bit: one node-local search handles < 2^31 points.
using point_id = std::int32_t;

/// A read-only view of `count` points of `dims` (2 or 3) coordinates stored point after point.
/// float32 coordinates are promoted to double when read, so a float32 view gives exactly the
/// neighbour list of a float64 view holding the same values.
class PointView {
public:
  PointView() = default;
  PointView(const double* xyz, std::size_t count, int dims)
      : data_(xyz), count_(count), dims_(dims), single_(false) {}
  PointView(const float* xyz, std::size_t count, int dims)
      : data_(xyz), count_(count), dims_(dims), single_(true) {}

  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  int dims() const { return dims_; }
  bool is_float32() const { return single_; }
  /// The caller's float64 coordinates (nullptr for a float32 view).
  const double* float64_data() const { return single_ ? nullptr : static_cast<const double*>(data_); }
  /// The caller's float32 coordinates (nullptr for a float64 view).
  const float* float32_data() const { return single_ ? static_cast<const float*>(data_) : nullptr; }

  /// Coordinate `axis` of point `i`, as a double.
  double operator()(std::size_t i, int axis) const {
    const std::size_t at = i * static_cast<std::size_t>(dims_) + static_cast<std::size_t>(axis);
    return single_ ? static_cast<double>(static_cast<const float*>(data_)[at])
                   : static_cast<const double*>(data_)[at];
  }

private:
  const void* data_ = nullptr;
  std::size_t count_ = 0;
  int dims_ = 3;
  bool single_ = false;
};

/// Points that own their coordinates (AoS float64).
struct PointSet {
  PointSet() = default;
  PointSet(int dims_, std::vector<double> xyz_, std::vector<std::int32_t> blocks_ = {})
      : dims(dims_), xyz(std::move(xyz_)), blocks(std::move(blocks_)) {}

  int dims = 3;
  std::vector<double> xyz;
  std::vector<std::int32_t> blocks;  ///< a block id per point when the input gave them (Peridigm), else empty

  std::size_t size() const { return dims > 0 ? xyz.size() / static_cast<std::size_t>(dims) : 0; }
  PointView view() const { return PointView(xyz.data(), size(), dims); }
};

/// Throws horizon::Error naming the first point with a NaN or infinite coordinate, or a view
/// whose dimension is not 2 or 3.
void validate(PointView points);

namespace detail {
/// validate() on `threads` cores (0: all).
void validate_points(PointView points, int threads);
/// validate_points less the test of the coordinates: 2 or 3 dimensions, fewer than 2^31 points.
void validate_point_shape(PointView points);
/// validate_points' test of the coordinates alone: throws naming the first non-finite one.
void check_finite(PointView points, int threads);
}  // namespace detail

/// Copies `points` (as doubles) into `into` from point `at` on (`into` holds room for them).
void copy_points(PointView points, PointSet& into, std::size_t at = 0);

/// `points` as a PointSet of doubles (float32 promoted).
PointSet to_point_set(PointView points);

}  // namespace horizon
