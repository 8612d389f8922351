// Many nodes: each MPI rank holds some points; every rank gets the families of the points it owns.
// Run: mpirun -np 2 ./distributed
#include <mpi.h>

#include <cstdio>
#include <vector>

#include <horizon/distributed.hpp>
#include <horizon/generate.hpp>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const horizon::PointSet all = horizon::lattice(20);  // every rank makes it; each keeps a share
  horizon::PointSet mine{3, {}};
  std::vector<std::int64_t> ids;
  for (std::size_t i = rank; i < all.size(); i += ranks) {
    mine.xyz.insert(mine.xyz.end(), all.xyz.begin() + 3 * i, all.xyz.begin() + 3 * i + 3);
    ids.push_back(static_cast<std::int64_t>(i));
  }
  horizon::DistributedOptions options;  // halo exchange over a recursive coordinate bisection
  options.search.horizon = 1.5075;
  horizon::OwnedRows owned = horizon::search_distributed(MPI_COMM_WORLD, mine.view(), ids, all.size(), options);
  long long entries = owned.rows.total(), total = 0;
  MPI_Reduce(&entries, &total, 1, MPI_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  if (rank == 0) std::printf("%d ranks, %lld entries\n", ranks, total);
  const bool exact = rank != 0 || total == horizon::lattice_entries(20, 3, 3.015);
  MPI_Finalize();
  return exact ? 0 : 1;
}
