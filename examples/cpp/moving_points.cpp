// Moving points: one search within horizon + skin, then exact lists of later positions from it.
#include <cstdio>

#include <horizon/generate.hpp>
#include <horizon/search.hpp>
#include <horizon/verlet_list.hpp>

int main() {
  horizon::PointSet points = horizon::lattice(20);  // spacing 0.5
  horizon::SearchOptions options;
  options.horizon = 0.75;
  horizon::VerletList verlet(points.view(), options, /*skin=*/0.1);
  int steps = 0;
  while (!verlet.needs_rebuild(points.view())) {  // until a point has moved skin / 2
    for (std::size_t i = 0; i < points.xyz.size(); i += 3) points.xyz[i] += 0.002 * (i % 7);
    horizon::NeighborList list = verlet.refresh(points.view());  // equal to a fresh search
    if (list != horizon::search(points.view(), options)) return 1;
    ++steps;
  }
  std::printf("%d steps from one search before a rebuild\n", steps);
  return steps > 0 ? 0 : 1;
}
