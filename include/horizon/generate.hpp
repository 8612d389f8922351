#pragma once
/// \file generate.hpp
/// The benchmark problems of DESIGN.md, reproducible from a seed on every platform.
#include <cstdint>

#include "horizon/metric.hpp"
#include "horizon/points.hpp"

namespace horizon {

/// n^dims points on a cube of side `side`, spacing h = side/n, point (i,j,k) at
/// ((i+1/2)h, (j+1/2)h, (k+1/2)h), x fastest.
PointSet lattice(int n, int dims = 3, double side = 10.0);

/// `count` points uniform in the cube [0, side)^dims.
PointSet random_cloud(std::size_t count, int dims = 3, std::uint64_t seed = 1, double side = 10.0);

/// `count` points in `clusters` Gaussian blobs of standard deviation sigma, centres uniform in
/// the cube [0, side)^dims.
PointSet clustered_cloud(std::size_t count, int clusters, double sigma, int dims = 3,
                         std::uint64_t seed = 1, double side = 10.0);

/// Exact number of entries in the full list of lattice(n, dims) at horizon m*h: the sum over
/// integer offsets v != 0 with metric(v) < m of prod_d (n - |v_d|).
std::int64_t lattice_entries(int n, int dims, double m, Metric metric = Metric::euclidean);

}  // namespace horizon
