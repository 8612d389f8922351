// Peridigm's bond filters: a pre-notched crack cuts every bond that crosses it.
#include <cstdio>

#include <horizon/bond_filter.hpp>
#include <horizon/generate.hpp>
#include <horizon/search.hpp>

int main() {
  horizon::PointSet points = horizon::lattice(20);  // the cube [0, 10]^3, spacing 0.5
  horizon::SearchOptions options;
  options.horizon = 1.5075;
  horizon::NeighborList list = horizon::search(points.view(), options);
  // A crack in the plane x = 5: along z through the whole cube, from y = 0 to y = 5 (the side runs
  // along bottom x normal = +y).
  horizon::RectangleFilter crack{.normal = {1, 0, 0}, .lower_left_corner = {5, 0, 0}, .bottom_unit_vector = {0, 0, 1},
                                 .bottom_length = 10, .side_length = 5};
  const long long before = list.total();
  list = horizon::filter_bonds(std::move(list), points.view(), {crack}, horizon::bond_reach(options, 3));
  std::printf("%lld bonds before, %lld after the crack\n", before, static_cast<long long>(list.total()));
  return list.total() < before ? 0 : 1;
}
