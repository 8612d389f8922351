// A program outside the horizon tree, built against the installed package.
#include <horizon/generate.hpp>
#include <horizon/search.hpp>
#include <horizon/version.hpp>

#include <cstdio>
#include <cstring>

int main() {
  const horizon::PointSet points = horizon::lattice(10);
  horizon::SearchOptions options;
  options.horizon = 1.5;  // m = 1.5 on a lattice of spacing 1
  const horizon::NeighborList list = horizon::search(points.view(), options);
  std::printf("%lld neighbours\n", static_cast<long long>(list.total()));
  // One version everywhere: the CMake package's, the header's and the linked library's.
  std::printf("package %s, header %s, library %s\n", PACKAGE_VERSION, HORIZON_VERSION_STRING, horizon::version());
  if (std::strcmp(PACKAGE_VERSION, HORIZON_VERSION_STRING) != 0 || std::strcmp(horizon::version(), PACKAGE_VERSION) != 0) return 1;
  return list.total() == horizon::lattice_entries(10, 3, 1.5) ? 0 : 1;
}
