#pragma once
// Small random problems for differential testing (tests/differential_test.cpp, and the MPI
// layer in tests/mpi_test.cpp): drawn from a seed, aimed at what nobody writes down, now and
// then in a periodic box.
#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "horizon/search.hpp"

namespace horizon::testing {

struct Problem {
  int dims = 3;
  std::vector<double> xyz;
  bool single = false;  // search the float32 rounding of the coordinates
  SearchOptions options;
  std::string describe() const {
    std::ostringstream out;
    out << xyz.size() / dims << " points, " << dims << "-D, horizon " << options.horizon << ", "
        << metric_name(options.metric) << ", k " << options.cells_per_horizon << (options.half ? ", half" : "")
        << (single ? ", float32" : "") << (options.queries ? ", queries " + std::to_string(options.queries) : "");
    if (options.box[0] > 0 || options.box[1] > 0 || options.box[2] > 0)
      out << ", box " << options.box[0] << "," << options.box[1] << "," << options.box[2];
    return out.str();
  }
};

inline Problem draw(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<std::uint64_t>(n)); };
  Problem p;
  p.dims = pick(2) ? 3 : 2;
  const int count = pick(8) == 0 ? pick(4) : pick(3000);
  const double side = std::pow(10.0, uniform(-3, 3));
  const double offset = pick(4) == 0 ? std::pow(10.0, uniform(0, 12)) * (pick(2) ? 1 : -1) : 0.0;
  p.options.horizon = side * std::pow(10.0, uniform(-3, 0.5));  // tiny to larger than the cloud
  p.options.metric = static_cast<Metric>(pick(3));
  p.options.cells_per_horizon = 1 + pick(3);
  p.options.half = pick(2);
  p.single = pick(5) == 0;
  const int shape = pick(6);
  for (int i = 0; i < count; ++i) {
    double x[3];
    for (int a = 0; a < p.dims; ++a) x[a] = uniform(0, side);
    if (shape == 1) {  // on exact multiples of the horizon or of the cell side
      const double unit = p.options.horizon / (pick(2) ? 1 : p.options.cells_per_horizon);
      for (int a = 0; a < p.dims; ++a) x[a] = unit * pick(12);
    } else if (shape == 2) {  // collinear
      const double t = uniform(0, side);
      for (int a = 0; a < p.dims; ++a) x[a] = t * (a + 1) * 0.25;
    } else if (shape == 3) {  // coplanar (z = 0, or y = x in 2-D)
      x[p.dims - 1] = p.dims == 3 ? 0.0 : x[0];
    } else if (shape == 4 && i > 0 && pick(3)) {  // duplicates of earlier points
      const int j = pick(i);
      for (int a = 0; a < p.dims; ++a) x[a] = p.xyz[static_cast<std::size_t>(j * p.dims + a)] - offset;
    }
    for (int a = 0; a < p.dims; ++a) p.xyz.push_back(x[a] + offset);
  }
  if (offset == 0 && pick(6) == 0) {  // a periodic box: some axes periodic, points wrapped into [0, L)
    for (int a = 0; a < p.dims; ++a)
      p.options.box[static_cast<std::size_t>(a)] = pick(3) ? side * uniform(0.5, 1.5) : 0.0;
    double shortest = std::numeric_limits<double>::infinity();
    for (int a = 0; a < p.dims; ++a) {
      const double period = p.options.box[static_cast<std::size_t>(a)];
      if (period == 0) continue;
      shortest = std::min(shortest, period);
      for (std::size_t i = static_cast<std::size_t>(a); i < p.xyz.size(); i += static_cast<std::size_t>(p.dims)) {
        p.xyz[i] = std::fmod(p.xyz[i], period);
        if (p.single && static_cast<double>(static_cast<float>(p.xyz[i])) >= period) p.xyz[i] = 0.0;
      }
    }
    p.options.horizon = std::min(p.options.horizon, 0.49 * shortest);
  }
  if (p.single)
    for (double& v : p.xyz) v = static_cast<double>(static_cast<float>(v));
  const bool periodic = p.options.box[0] > 0 || p.options.box[1] > 0 || p.options.box[2] > 0;
  if (count > 0 && !periodic && pick(6) == 0) p.options.queries = static_cast<std::size_t>(1 + pick(count));
  return p;
}

inline int problem_count(int fallback = 1000) {
  const char* value = std::getenv("HORIZON_DIFFERENTIAL_PROBLEMS");
  return value ? std::atoi(value) : fallback;
}

inline std::uint64_t seed() {
  const char* value = std::getenv("HORIZON_DIFFERENTIAL_SEED");
  return value ? std::strtoull(value, nullptr, 10) : 20261123;
}

}  // namespace horizon::testing
