#pragma once
// Which periodic images of a point can be within the horizon of a point of the box: each point
// within the horizon of a periodic face, shifted by the period across it (corners: every
// combination). Shared by the CPU (reference_search.cpp) and the GPU (cuda/periodic_images.cuh),
// so both make the same images.
#include "horizon/metric.hpp"  // HORIZON_HOST_DEVICE
#include "horizon/search.hpp"

namespace horizon::detail {

struct PeriodicBox {
  int dims = 3;
  double period[3] = {0, 0, 0};  ///< 0: open
  double reach[3] = {0, 0, 0};   ///< how far from a face a point has an image across it

  PeriodicBox(const SearchOptions& options, int point_dims) : dims(point_dims) {
    for (int a = 0; a < dims; ++a) {
      period[a] = options.box[a];
      // The margin keeps every image whose rounded coordinate could be within the horizon.
      reach[a] = options.horizon + period[a] * 0x1p-40;
    }
  }

  /// Whether the point at xyz[0 .. dims) lies in [0, period) on every periodic axis.
  HORIZON_HOST_DEVICE bool contains(const double* xyz) const {
    for (int a = 0; a < dims; ++a)
      if (period[a] > 0 && !(xyz[a] >= 0 && xyz[a] < period[a])) return false;
    return true;
  }

  /// The shifts along axis a of the images of a point at x: 0, then +period near the low face
  /// and -period near the high one; returns how many (1 to 3).
  HORIZON_HOST_DEVICE int axis_shifts(int a, double x, double* shifts) const {
    int count = 1;
    shifts[0] = 0;
    if (a >= dims || period[a] == 0) return count;
    if (x < reach[a]) shifts[count++] = period[a];
    if (x >= period[a] - reach[a]) shifts[count++] = -period[a];
    return count;
  }

  /// The number of images of the point at xyz[0 .. dims).
  HORIZON_HOST_DEVICE int image_count(const double* xyz) const {
    int product = 1;
    double unused[3];
    for (int a = 0; a < dims; ++a) product *= axis_shifts(a, xyz[a], unused);
    return product - 1;
  }

  /// Writes the shifts of the images of the point at xyz[0 .. dims) (every combination but
  /// none); returns how many, at most 26.
  HORIZON_HOST_DEVICE int image_shifts(const double* xyz, double (*shift)[3]) const {
    double shifts[3][3];
    int count[3];
    for (int a = 0; a < 3; ++a) count[a] = axis_shifts(a, a < dims ? xyz[a] : 0.0, shifts[a]);
    int images = 0;
    for (int sx = 0; sx < count[0]; ++sx)
      for (int sy = 0; sy < count[1]; ++sy)
        for (int sz = 0; sz < count[2]; ++sz)
          if (sx != 0 || sy != 0 || sz != 0) {
            shift[images][0] = shifts[0][sx];
            shift[images][1] = shifts[1][sy];
            shift[images][2] = shifts[2][sz];
            ++images;
          }
    return images;
  }
};

}  // namespace horizon::detail
