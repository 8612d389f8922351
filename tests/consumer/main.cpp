// A program outside the horizon tree, built against the installed package.
#include <horizon/generate.hpp>
#include <horizon/search.hpp>

#include <cstdio>

int main() {
  const horizon::PointSet points = horizon::lattice(10);
  horizon::SearchOptions options;
  options.horizon = 1.5;  // m = 1.5 on a lattice of spacing 1
  const horizon::NeighborList list = horizon::search(points.view(), options);
  std::printf("%lld neighbours\n", static_cast<long long>(list.total()));
  return list.total() == horizon::lattice_entries(10, 3, 1.5) ? 0 : 1;
}
