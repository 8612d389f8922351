// Several GPUs in one process: the points are cut into one part per GPU, each searched with its
// halo on its own GPU. search() brings the rows back in input order (the same list as one GPU
// gives); search_device_parts() leaves each part's rows on its GPU, for a solver that lives there.
#include <cstdio>

#include <horizon/cuda.hpp>
#include <horizon/generate.hpp>
#include <horizon/parts.hpp>
#include <horizon/search.hpp>

int main() {
  const horizon::PointSet points = horizon::lattice(100);
  horizon::SearchOptions options;
  options.horizon = 0.15;
  const std::int64_t expected = horizon::lattice_entries(100, 3, 1.5);

  // Without a GPU, the same parts on the CPU, one after another.
  const int gpus = horizon::cuda_device_count();
  if (gpus == 0) {
    std::int64_t total = 0;
    for (const horizon::OwnedPart& part : horizon::search_in_parts(points.view(), 2, options)) {
      std::printf("part: %zu points + %zu halo, %lld entries\n", part.ids.size(), part.halo,
                  static_cast<long long>(part.rows.total()));
      total += part.rows.total();
    }
    return total == expected ? 0 : 1;
  }

  options.backend = horizon::Backend::cuda;
  options.devices.resize(gpus < 2 ? 2 : gpus);  // with one GPU: two parts on it
  for (std::size_t p = 0; p < options.devices.size(); ++p) options.devices[p] = static_cast<int>(p) % gpus;
  horizon::SearchStats stats;
  const horizon::NeighborList list = horizon::search(points.view(), options, &stats);
  for (const horizon::PartStats& part : stats.parts)
    std::printf("GPU %d: %zu points + %zu halo, %.3f s\n", part.device, part.owned, part.halo, part.seconds);

  // Rows left on the GPUs: part.rows (CSR, global ids) and part.device_ids on part.device.
  std::int64_t total = 0;
  for (const horizon::DevicePart& part : horizon::search_device_parts(points.view(), options)) {
    std::printf("GPU %d keeps the rows of %zu points: %lld entries\n", part.device, part.ids.size(),
                static_cast<long long>(part.rows.total()));
    total += part.rows.total();
  }
  return list.total() == expected && total == expected ? 0 : 1;
}
