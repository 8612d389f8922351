// Several GPUs in one process: the points are cut into one part per GPU, each searched with its
// halo on its own GPU; the rows come back in input order, the same list as one GPU gives.
#include <cstdio>

#include <horizon/cuda.hpp>
#include <horizon/generate.hpp>
#include <horizon/search.hpp>

int main() {
  const int gpus = horizon::cuda_device_count();
  if (gpus == 0) {
    std::printf("no GPU: nothing to show\n");
    return 0;
  }
  const horizon::PointSet points = horizon::lattice(100);
  horizon::SearchOptions options;
  options.horizon = 0.15;
  options.backend = horizon::Backend::cuda;
  options.devices.resize(gpus < 2 ? 2 : gpus);  // with one GPU: two parts on it
  for (std::size_t p = 0; p < options.devices.size(); ++p) options.devices[p] = static_cast<int>(p) % gpus;
  horizon::SearchStats stats;
  const horizon::NeighborList list = horizon::search(points.view(), options, &stats);
  for (const horizon::PartStats& part : stats.parts)
    std::printf("GPU %d: %zu points + %zu halo, %.3f s\n", part.device, part.owned, part.halo, part.seconds);
  return list.total() == horizon::lattice_entries(100, 3, 1.5) ? 0 : 1;
}
