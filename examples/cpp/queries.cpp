// Query points against a separate reference set: row q holds every reference within the horizon.
#include <cstdio>

#include <horizon/generate.hpp>
#include <horizon/search.hpp>

int main() {
  horizon::PointSet references = horizon::lattice(30);              // 27,000 points
  horizon::PointSet probes = horizon::random_cloud(100, 3, /*seed=*/5);  // 100 probes in the cube
  horizon::SearchOptions options;
  options.horizon = 0.5;
  horizon::NeighborList list = horizon::search(probes.view(), references.view(), options);
  std::printf("%zu probes; the first sees %zu lattice points\n", list.size(), list.row(0).size());
  return list.size() == probes.size() ? 0 : 1;
}
