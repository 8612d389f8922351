#pragma once
// Moving points between ranks: every exchange strategy sends points packed as
// (x, y, z, global id[, radius]) in doubles (ids below 2^53 are exact) and counts what it sends.
#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

#include "horizon/points.hpp"

namespace horizon::detail {

/// x, y, z, global id, radius: the radius travels only with per-point radii (`width` 5 below;
/// else 4 doubles a point go on the wire).
using Packed = std::array<double, 5>;

/// Point i of `points` packed with its global id and radius.
inline Packed pack(PointView points, std::size_t i, std::int64_t id, double radius) {
  Packed p{0, 0, 0, static_cast<double>(id), radius};
  for (int a = 0; a < points.dims(); ++a) p[static_cast<std::size_t>(a)] = points(i, a);
  return p;
}

struct Traffic {
  std::int64_t bytes = 0, messages = 0;
};

/// All-to-all: outgoing[r] goes to rank r; returns what every rank sent here. Counts first
/// (MPI_Alltoall), then the points (MPI_Alltoallv).
std::vector<Packed> exchange_all(MPI_Comm comm, const std::vector<std::vector<Packed>>& outgoing, int width,
                                 Traffic& traffic);

/// Neighbourhood exchange over a graph communicator whose sources and destinations are both
/// `partners`: outgoing[k] goes to partners[k]. Counts first, then the points.
std::vector<Packed> exchange_with(MPI_Comm graph, const std::vector<std::vector<Packed>>& outgoing, int width,
                                  Traffic& traffic);

}  // namespace horizon::detail
