// The host side of the GPU parts' copy, without a GPU: place_rows over 64 MB chunks of two
// parts whose rows alternate in the assembled list (as a lattice cut across x gives), against
// one memcpy of the same bytes. Rows of 120 ids, 2 x 10^6 rows (960 MB). RUN=L (default 1):
// the parts alternate every L rows instead (a lattice cut across x gives runs of a line's half;
// L must divide 10^6).
// Build: g++ -O2 -std=c++20 -fopenmp -Iinclude -Isrc place_rows_bench.cpp build-dev/src/libhorizon.a -lhwy
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "core/device_part.hpp"
#include "core/parallel_copy.hpp"
#include <omp.h>
using namespace horizon;

static double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

int main() {
  const std::size_t rows = 2'000'000, length = 120, per_part = rows / 2;
  const std::size_t run = std::getenv("RUN") ? std::strtoul(std::getenv("RUN"), nullptr, 10) : 1;
  Buffer<std::int64_t> at(rows + 1), local(per_part + 1);
  for (std::size_t i = 0; i <= rows; ++i) at[i] = static_cast<std::int64_t>(i * length);
  for (std::size_t r = 0; r <= per_part; ++r) local[r] = static_cast<std::int64_t>(r * length);
  std::vector<std::vector<point_id>> global(2, std::vector<point_id>(per_part));
  std::vector<std::uint8_t> keep(per_part, 1);
  for (std::size_t r = 0; r < per_part; ++r) 
    for (std::size_t p = 0; p < 2; ++p) global[p][r] = point_id(r / run * 2 * run + p * run + r % run);
  std::vector<point_id> staged(per_part * length);
  for (std::size_t e = 0; e < staged.size(); ++e) staged[e] = point_id(e);
  Buffer<point_id> indices(rows * length), copy(rows * length);
  const double touch_start = now();
  detail::parallel_touch(indices.data(), indices.size() * sizeof(point_id));
  detail::parallel_touch(copy.data(), copy.size() * sizeof(point_id));
  std::printf("faulting in 2 x %.2f GB: %.1f ms\n", indices.size() * 4 / 1e9, (now() - touch_start) * 1e3);
  const std::size_t chunk_rows = (std::size_t{64} << 20) / sizeof(point_id) / length;
  for (int round = 0; round < 5; ++round) {
    double t0 = now();
    for (std::size_t first = 0; first < per_part; first += chunk_rows)
      for (int p = 0; p < 2; ++p) {
        const std::size_t last = std::min(per_part, first + chunk_rows);
        const detail::PartRows part{nullptr, keep, global[p]};
        detail::place_rows(part, local.data(), first, last, staged.data() + local[first], at.data(), indices.data());
      }
    const double placed = now() - t0;
    t0 = now();
    for (int p = 0; p < 2; ++p) std::memcpy(copy.data() + p * staged.size(), staged.data(), staged.size() * sizeof(point_id));
    const double copied = now() - t0;
    std::printf("place_rows %.1f ms (%.1f GB/s), one memcpy of the same bytes %.1f ms, threads %d\n", placed * 1e3,
                indices.size() * 4 / placed / 1e9, copied * 1e3, omp_get_max_threads());
  }
  for (std::size_t i = 0; i < rows; i += 99991)
    if (indices[at[i]] != point_id((i / (2 * run) * run + i % run) * length)) return std::printf("wrong row %zu\n", i), 1;
}
