// A periodic box: distances to the nearest image, as scipy's cKDTree(boxsize=...).
#include <cstdio>

#include <horizon/generate.hpp>
#include <horizon/search.hpp>

int main() {
  horizon::PointSet points = horizon::random_cloud(10000, 3, /*seed=*/7);  // in [0, 10)^3
  horizon::SearchOptions options;
  options.horizon = 0.8;
  options.box = {10, 10, 0};  // periodic in x and y (period 10), open in z
  horizon::NeighborList periodic = horizon::search(points.view(), options);
  options.box = {0, 0, 0};
  horizon::NeighborList open = horizon::search(points.view(), options);
  std::printf("periodic: %lld entries, open: %lld\n", static_cast<long long>(periodic.total()),
              static_cast<long long>(open.total()));
  return periodic.total() > open.total() ? 0 : 1;  // the images across x and y add pairs
}
