#pragma once
// Point sets the oracle tests run every backend on: each is small enough for brute force and
// chosen to break a particular assumption of the grid.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/search.hpp"

namespace horizon::testing {

struct Dataset {
  std::string name;
  PointSet points;
  double horizon;
};

/// The options of a search of `data` (serial unless told).
inline SearchOptions options_for(const Dataset& data, Metric metric, int k, bool half,
                                 Backend backend = Backend::serial) {
  SearchOptions options;
  options.horizon = data.horizon;
  options.metric = metric;
  options.cells_per_horizon = k;
  options.half = half;
  options.backend = backend;
  return options;
}

inline PointSet integer_cloud(std::size_t count, int dims, int side, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  PointSet set{dims, {}};
  for (std::size_t i = 0; i < count * static_cast<std::size_t>(dims); ++i)
    set.xyz.push_back(static_cast<double>(rng() % static_cast<std::uint64_t>(side)));
  return set;
}

inline std::vector<Dataset> datasets(int dims) {
  std::vector<Dataset> all;
  all.push_back({"random", random_cloud(1200, dims, 7), dims == 3 ? 1.6 : 0.5});
  all.push_back({"clustered", clustered_cloud(1200, 6, 0.4, dims, 3), 0.25});
  // Dense: hundreds of candidates per cell, where rows come from a stencil sorted per cell.
  all.push_back({"dense", random_cloud(1500, dims, 13), dims == 3 ? 3.0 : 2.5});
  // Density growing along x, ids in no spatial order: rows of every length from 0 to about 70,
  // so the row sort meets each of its sizes (one to four vectors, and longer).
  PointSet graded = random_cloud(1500, dims, 17);
  for (std::size_t i = 0; i < graded.size(); ++i) graded.xyz[i * dims] = 10.0 * std::cbrt(graded.xyz[i * dims] / 10.0);
  all.push_back({"graded", graded, dims == 3 ? 1.6 : 0.7});
  const int n = dims == 3 ? 9 : 30;
  all.push_back({"lattice_m1.5", lattice(n, dims), 1.5 * 10.0 / n});
  all.push_back({"lattice_m3.015", lattice(n, dims), 3.015 * 10.0 / n});
  // Integer coordinates with an integer horizon: many pairs exactly on the horizon sphere (excluded)
  // and points exactly on cell borders.
  all.push_back({"integer_ties", integer_cloud(700, dims, dims == 3 ? 9 : 25, 11), 3.0});
  // Partners at relative distances 1 +- 1e-5 ... 1e-9 and 1 from their centre, along an axis
  // (as near the horizon in every metric) and in a random direction: pairs inside and outside
  // the GPU's single-precision screen's band, which the double test must decide.
  PointSet near{dims, {}};
  std::mt19937_64 pick(21);
  std::normal_distribution<double> normal;
  const double offsets[] = {-1e-5, -1e-6, -1e-7, -3e-8, -1e-9, 0, 1e-9, 3e-8, 1e-7, 1e-6, 1e-5};
  for (int centre = 0; centre < 64; ++centre) {
    double c[3] = {0, 0, 0};
    for (int a = 0, rest = centre; a < dims; ++a, rest /= dims == 3 ? 4 : 8) c[a] = 3.0 * (rest % (dims == 3 ? 4 : 8));
    near.xyz.insert(near.xyz.end(), c, c + dims);
    for (double t : offsets)
      for (int random_direction = 0; random_direction < 2; ++random_direction) {
        double v[3] = {0, 0, 0}, length = 0;
        for (int a = 0; a < dims; ++a) {
          v[a] = random_direction ? normal(pick) : (a == static_cast<int>(pick() % dims) ? 1.0 : 0.0);
          length += v[a] * v[a];
        }
        if (length == 0) v[0] = length = 1;
        for (int a = 0; a < dims; ++a) near.xyz.push_back(c[a] + (1 + t) * v[a] / std::sqrt(length));
      }
  }
  all.push_back({"near_horizon", near, 1.0});
  // Every point three times: coincident points are each other's neighbours.
  PointSet triple{dims, {}};
  const PointSet base = random_cloud(150, dims, 5);
  for (int copy = 0; copy < 3; ++copy) triple.xyz.insert(triple.xyz.end(), base.xyz.begin(), base.xyz.end());
  all.push_back({"duplicates", triple, 2.0});
  // A single point and no points.
  all.push_back({"one_point", PointSet{dims, std::vector<double>(static_cast<std::size_t>(dims), 1.5)}, 1.0});
  all.push_back({"empty", PointSet{dims, {}}, 1.0});
  // Two clumps 10^12 apart with a horizon of 10^-3: a dense grid would need 10^45 cells.
  PointSet far{dims, {}};
  std::mt19937_64 rng(9);
  for (int i = 0; i < 200; ++i)
    for (int a = 0; a < dims; ++a)
      far.xyz.push_back((i % 2 ? 1e12 : 0.0) + static_cast<double>(rng() % 2000) * 1e-6);
  all.push_back({"huge_extent", far, 1e-3});
  return all;
}

}  // namespace horizon::testing
