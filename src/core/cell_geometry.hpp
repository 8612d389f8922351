#pragma once
// A periodic cell made ready for searching: checked, its open axes' missing vectors completed,
// inverted, and the distance between each pair of opposite faces. And the one formula for an
// entry's vector, which the search and the oracle share so that both take the same decisions.
#include <cstdint>

#include "horizon/cell.hpp"
#include "horizon/metric.hpp"  // HORIZON_HOST_DEVICE

namespace horizon::detail {

struct CellFrame {
  int dims = 3;
  double vectors[3][3] = {};  ///< rows: the cell vectors (open axes' zero vectors completed)
  double inverse[3][3] = {};  ///< fractional f = x . inverse
  double height[3] = {};      ///< distance between the faces spanned by the other vectors
  bool pbc[3] = {};
  double scale = 0;           ///< largest |vector| component of a periodic axis (rounding margins)

  /// Checks `cell` for points of `dims` coordinates: Error naming the entry or axis when an
  /// entry is not finite, a periodic axis has a vector of zero length, or the (completed) cell
  /// is left-handed or nearly singular. A cell with no periodic axis is not used (identity).
  CellFrame(const Cell& cell, int dims);

  /// Fractional coordinate along axis a of the point at x.
  HORIZON_HOST_DEVICE double fractional(const double* x, int a) const {
    double f = 0;
    for (int b = 0; b < dims; ++b) f += x[b] * inverse[b][a];
    return f;
  }
};

/// g . cell along axis a (of `dims`): how far whole cells g move a point.
template <class Int>
HORIZON_HOST_DEVICE inline double cells_along(const Int* g, const CellFrame& cell, int dims, int a) {
  double moved = 0;
  for (int k = 0; k < dims; ++k) moved += static_cast<double>(g[k]) * cell.vectors[k][a];
  return moved;
}

/// D = x_j + S . cell - x_i for points of D coordinates, S an integer shift per axis.
template <int D>
HORIZON_HOST_DEVICE inline void pair_vector(const double* xi, const double* xj, const std::int32_t* shift,
                                            const CellFrame& cell, double* out) {
  for (int a = 0; a < D; ++a) out[a] = (xj[a] - xi[a]) + cells_along(shift, cell, D, a);
}

/// Whether shift S (D components) is "positive": its first non-zero component is.
template <int D>
HORIZON_HOST_DEVICE inline bool positive_shift(const std::int32_t* shift) {
  for (int a = 0; a < D; ++a)
    if (shift[a] != 0) return shift[a] > 0;
  return false;
}

}  // namespace horizon::detail
