// Getting started: the families of 8,000 lattice points within 3.015 lattice spacings.
#include <cstdio>

#include <horizon/generate.hpp>
#include <horizon/search.hpp>

int main() {
  horizon::PointSet points = horizon::lattice(20);  // 20^3 points on a cube of side 10, spacing 0.5
  horizon::SearchOptions options;
  options.horizon = 3.015 * 0.5;                    // pairs closer than this (strictly)
  horizon::NeighborList list = horizon::search(points.view(), options);
  std::printf("%zu points, %lld entries; point 0 has %zu neighbours, the first is %d\n", list.size(),
              static_cast<long long>(list.total()), list.row(0).size(), list.row(0)[0]);
  return list.total() == horizon::lattice_entries(20, 3, 3.015) ? 0 : 1;  // the closed form
}
