#include "cell_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "horizon/error.hpp"

namespace horizon::detail {
namespace {

const char* vector_name(int k) { return k == 0 ? "a" : k == 1 ? "b" : "c"; }

double dot(const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
double norm(const double* u) { return std::sqrt(dot(u, u)); }
void cross(const double* u, const double* v, double* out) {
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}
void scale_to(double* u, double length) {
  const double n = norm(u);
  for (int a = 0; a < 3; ++a) u[a] *= length / n;
}

/// A unit vector perpendicular to u (|u| > 0).
void perpendicular(const double* u, double* out) {
  // Cross with the coordinate axis least aligned with u.
  double axis[3] = {0, 0, 0};
  int least = 0;
  for (int a = 1; a < 3; ++a)
    if (std::fabs(u[a]) < std::fabs(u[least])) least = a;
  axis[least] = 1;
  cross(u, axis, out);
  scale_to(out, 1.0);
}

}  // namespace

CellFrame::CellFrame(const Cell& cell, int point_dims) : dims(point_dims) {
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(cell.vectors[k][a]))
        throw Error(std::string("cell: vector ") + vector_name(k) + " has a non-finite component " + std::to_string(a));
  for (int k = dims; k < 3; ++k)
    if (cell.pbc[k])
      throw Error(std::string("cell: pbc on vector ") + vector_name(k) + " but the points are " + std::to_string(dims) +
                  "-D");
  int periodic = 0;
  for (int k = 0; k < dims; ++k) {
    pbc[k] = cell.pbc[k];
    periodic += pbc[k];
  }
  // The periodic vectors as given (in 2-D their third components 0); open axes are completed
  // perpendicular to them, so that what an open axis's vector says never matters.
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) vectors[k][a] = k < dims && a < dims && pbc[k] ? cell.vectors[k][a] : 0.0;
  for (int k = 0; k < dims; ++k) {
    if (!pbc[k]) continue;
    if (norm(vectors[k]) == 0)
      throw Error(std::string("cell: vector ") + vector_name(k) + " has zero length but its axis is periodic");
    for (int a = 0; a < dims; ++a) scale = std::max(scale, std::fabs(vectors[k][a]));
  }
  if (dims == 2) vectors[2][2] = 1;  // the plane's normal: 2-D cells are 3-D ones of unit depth
  int open[3], n_open = 0, given[3], n_given = 0;
  for (int k = 0; k < dims; ++k) (pbc[k] ? given[n_given++] : open[n_open++]) = k;
  const double length = scale > 0 ? scale : 1.0;
  if (periodic == 0) {
    for (int k = 0; k < dims; ++k) vectors[k][k] = 1;
  } else if (dims == 3 && n_open == 1) {
    // c' along a x b (in cyclic order, so that the cell stays right-handed).
    const int k = open[0];
    cross(vectors[(k + 1) % 3], vectors[(k + 2) % 3], vectors[k]);
    if (norm(vectors[k]) == 0)
      throw Error(std::string("cell: vectors ") + vector_name((k + 1) % 3) + " and " + vector_name((k + 2) % 3) +
                  " are parallel");
    scale_to(vectors[k], length);
  } else if (dims == 3 && n_open == 2) {
    const int p = given[0], k1 = (p + 1) % 3, k2 = (p + 2) % 3;
    perpendicular(vectors[p], vectors[k1]);
    scale_to(vectors[k1], length);
    cross(vectors[p], vectors[k1], vectors[k2]);
    scale_to(vectors[k2], length);
  } else if (dims == 2 && n_open == 1) {
    const int p = given[0], k = open[0];
    // Rotated by +90 degrees from a when b is open, by -90 degrees from b when a is: right-handed.
    const double sign = k == 1 ? 1.0 : -1.0;
    vectors[k][0] = -sign * vectors[p][1];
    vectors[k][1] = sign * vectors[p][0];
    scale_to(vectors[k], length);
  }
  double cofactor[3][3];  // rows: b x c, c x a, a x b
  for (int k = 0; k < 3; ++k) cross(vectors[(k + 1) % 3], vectors[(k + 2) % 3], cofactor[k]);
  const double det = dot(vectors[0], cofactor[0]);
  const double size = norm(vectors[0]) * norm(vectors[1]) * norm(vectors[2]);
  if (periodic > 0) {
    if (det < 0)
      throw Error("cell: the vectors are left-handed (det = " + std::to_string(det) +
                  " < 0); swap two of them, or negate one");
    if (!(det > 1e-10 * size))
      throw Error("cell: the vectors are (nearly) linearly dependent: volume " + std::to_string(det) +
                  " against |a| |b| |c| = " + std::to_string(size));
  }
  // x = f . vectors, so f = x . inverse with inverse[b][a] = cofactor[a][b] / det.
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) inverse[b][a] = cofactor[a][b] / det;
  for (int k = 0; k < 3; ++k) height[k] = det / norm(cofactor[k]);
}

}  // namespace horizon::detail
