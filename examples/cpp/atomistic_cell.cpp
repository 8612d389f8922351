// A periodic cell of any shape, a cutoff of several cells, and each entry's shift, distance and
// vector: silicon's primitive cell (2 atoms, fcc vectors) with a 5 angstrom cutoff.
#include <cmath>
#include <cstdio>

#include <horizon/search.hpp>

int main() {
  const double a = 5.43, q = a / 4;  // the cubic lattice constant; the second atom at (a/4, a/4, a/4)
  const horizon::PointSet atoms(3, {0, 0, 0, q, q, q});
  horizon::SearchOptions options;
  options.horizon = 5.0;
  options.cell.vectors = {{{0, a / 2, a / 2}, {a / 2, 0, a / 2}, {a / 2, a / 2, 0}}};
  options.cell.pbc = {true, true, true};
  options.outputs = {.shifts = true, .distances = true, .vectors = true};
  const horizon::NeighborList list = horizon::search(atoms.view(), options);
  // Diamond's shells within 5 angstrom: 4 at a sqrt(3)/4, 12 at a/sqrt(2), 12 at a sqrt(11)/4.
  int shells[3] = {0, 0, 0};
  const double radius[3] = {a * std::sqrt(3.0) / 4, a / std::sqrt(2.0), a * std::sqrt(11.0) / 4};
  for (std::int64_t e = 0; e < list.total(); ++e)
    for (int s = 0; s < 3; ++s) shells[s] += std::fabs(list.distances()[e] - radius[s]) < 1e-9;
  const std::int32_t* first = list.shifts().data();
  std::printf("%lld entries for 2 atoms; per atom %d, %d, %d in the first three shells; the first: j = %d, "
              "S = (%d, %d, %d), d = %.4f\n",
              static_cast<long long>(list.total()), shells[0] / 2, shells[1] / 2, shells[2] / 2, list.indices()[0],
              first[0], first[1], first[2], list.distances()[0]);
  return shells[0] == 8 && shells[1] == 24 && shells[2] == 24 && list.total() == 56 ? 0 : 1;
}
