#include <hwy/highway.h>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>
#include <bit>
#include <cstdint>
using point_id = std::int32_t;
#include "core/sort_network-inl.h"
#include "core/store_selected-inl.h"
namespace hn = hwy::HWY_NAMESPACE;
using namespace horizon::detail::HWY_NAMESPACE;
// Simulated fill: 5 compress-stores of up to 8 lanes into row, then sort.
int main() {
  const hn::ScalableTag<point_id> d;
  const hn::CappedTag<point_id, 8> d8;
  std::mt19937 rng(1);
  const int R = 4096;
  std::vector<point_id> src(R * 40); for (auto& v : src) v = rng() % 1000000;
  std::vector<unsigned> masks(R * 5); for (auto& m : masks) m = rng() & 0xFF;
  std::vector<point_id> out(R * 64);
  alignas(64) point_id bufA[128], bufB[128];
  for (int variant = 0; variant < 2; ++variant)
  for (int rep = 0; rep < 3; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    long total = 0;
    point_id* pending = nullptr; std::int64_t pending_found = 0; point_id* pending_place = nullptr;
    for (int it = 0; it < 200; ++it)
      for (int r = 0; r < R; ++r) {
        point_id* row = (variant == 1 && (r & 1)) ? bufB : bufA;
        std::int64_t found = 0;
        for (int s = 0; s < 5; ++s) {
          unsigned keep = masks[r * 5 + s] & 0x1F;  // ~2.5 of 5 -> ~12 per row... use more bits
          keep = masks[r * 5 + s];
          keep &= 0x0F | (keep >> 4 & 0x3) << 4;
          StoreSelected(d8, hn::LoadU(d8, src.data() + r * 40 + s * 8), keep, row + found);
          found += std::popcount(keep);
        }
        if (found > 32) found = 32;
        point_id* place = out.data() + (r * 64 % (R * 64 - 64));
        if (variant == 0) {
          SortShortRowTo(row, found, point_id{-1}, place, found);
        } else {
          if (pending) SortShortRowTo(pending, pending_found, point_id{-1}, pending_place, pending_found);
          pending = row; pending_found = found; pending_place = place;
        }
        total += found;
      }
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    printf("variant %d: %.1f ns per row (avg %.1f ids)\n", variant, s / (200.0 * R) * 1e9, total / (200.0 * R));
  }
}
