#include "horizon/generate.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace horizon {

namespace {

// mt19937_64 is specified bit for bit by the standard; the distributions are not, so the
// conversions to doubles are spelled out here.
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

double standard_normal(std::mt19937_64& rng) {
  const double u = 1.0 - uniform01(rng);  // (0, 1]
  const double v = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * v);
}

}  // namespace

PointSet lattice(int n, int dims, double side) {
  PointSet set{dims, {}};
  const double h = side / n;
  const int nz = dims == 3 ? n : 1;
  set.xyz.reserve(static_cast<std::size_t>(n) * n * nz * dims);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        set.xyz.push_back((i + 0.5) * h);
        set.xyz.push_back((j + 0.5) * h);
        if (dims == 3) set.xyz.push_back((k + 0.5) * h);
      }
  return set;
}

PointSet random_cloud(std::size_t count, int dims, std::uint64_t seed, double side) {
  std::mt19937_64 rng(seed);
  PointSet set{dims, std::vector<double>(count * static_cast<std::size_t>(dims))};
  for (double& x : set.xyz) x = side * uniform01(rng);
  return set;
}

PointSet clustered_cloud(std::size_t count, int clusters, double sigma, int dims,
                         std::uint64_t seed, double side) {
  std::mt19937_64 rng(seed);
  std::vector<double> centres(static_cast<std::size_t>(clusters) * dims);
  for (double& c : centres) c = side * uniform01(rng);
  PointSet set{dims, {}};
  set.xyz.reserve(count * static_cast<std::size_t>(dims));
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t c = i % static_cast<std::size_t>(clusters);
    for (int a = 0; a < dims; ++a)
      set.xyz.push_back(centres[c * dims + a] + sigma * standard_normal(rng));
  }
  return set;
}

std::int64_t lattice_entries(int n, int dims, double m, Metric metric) {
  const int reach = static_cast<int>(std::ceil(m));
  const int reach_z = dims == 3 ? reach : 0;
  std::int64_t total = 0;
  for (int vz = -reach_z; vz <= reach_z; ++vz)
    for (int vy = -reach; vy <= reach; ++vy)
      for (int vx = -reach; vx <= reach; ++vx) {
        if (vx == 0 && vy == 0 && vz == 0) continue;
        const double d = metric_accumulate<Metric::euclidean>(vx, vy, vz);
        const double l1 = std::abs(vx) + std::abs(vy) + std::abs(vz);
        const double linf = std::max({std::abs(vx), std::abs(vy), std::abs(vz)});
        const bool inside = metric == Metric::euclidean ? d < m * m
                            : metric == Metric::manhattan ? l1 < m
                                                          : linf < m;
        if (!inside || std::abs(vx) >= n || std::abs(vy) >= n || std::abs(vz) >= n) continue;
        std::int64_t pairs = static_cast<std::int64_t>(n - std::abs(vx)) * (n - std::abs(vy));
        if (dims == 3) pairs *= n - std::abs(vz);
        total += pairs;
      }
  return total;
}

}  // namespace horizon
