#include "part_lists.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <bit>
#include <string>
#include <utility>

#include "horizon/error.hpp"
#include "horizon/grid.hpp"

namespace horizon::detail {

PartCut::PartCut(PointView points, int count, double horizon) : count_(count) {
  if (count < 1 || count > 64)  // the halo bits
    throw Error(std::to_string(count) + " parts: from 1 to 64 are supported");
  // All the points, or 2^17 drawn by a fixed hash of the draw's number: a stride aliases with a
  // lattice's period (every 15th point of a lattice 100 wide has x in steps of 5: one part of two
  // got 55 % of the points).
  constexpr std::size_t most = std::size_t{1} << 17;
  const std::size_t n = points.size(), draws = std::min(n, most);
  PointSet sample{points.dims(), std::vector<double>(draws * static_cast<std::size_t>(points.dims()))};
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < draws; ++k) {
    std::uint64_t h = k + 0x9e3779b97f4a7c15ull;  // splitmix64
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    const std::size_t i = n > most ? static_cast<std::size_t>((h ^ (h >> 31)) % n) : k;
    for (int a = 0; a < points.dims(); ++a) sample.xyz[k * points.dims() + a] = points(i, a);
  }
  const Bounds box = bounds_of(points, omp_get_max_threads());
  boxes_ = Decomposition::rcb(box, sample.view(), count);
  reach_ = halo_reach(box, points.dims(), horizon);
}

int PartCut::parts_of(PointView points, std::size_t i, std::uint64_t& halo) const {
  double x[3] = {0, 0, 0};
  for (int a = 0; a < points.dims(); ++a) x[a] = points(i, a);
  return boxes_.owner_and_near(x, reach_, halo);
}

// Each thread counts, then writes, a contiguous range of ids for every part at once, so each
// list ascends. The first pass keeps each point's part in a byte, marked when the point is in
// some halo: the second walks the cuts again for those points alone.
std::vector<PartLists> PartCut::lists(PointView points, bool local) const {
  const std::size_t n = points.size();
  const int count = count_;
  std::vector<PartLists> parts(static_cast<std::size_t>(count));
  const int pieces = omp_get_max_threads();
  // Per piece and part: owned, halo and local points, counted then turned into write cursors.
  std::vector<std::array<std::size_t, 3>> at(static_cast<std::size_t>(pieces * count), {0, 0, 0});
  auto range = [&](int t) { return std::pair{n * t / pieces, n * (t + 1) / pieces}; };
  constexpr std::uint8_t in_halos = 0x80;
  ScratchBuffer<std::uint8_t> owner(n);
  auto each_part_of = [&](std::size_t i, auto&& visit) {  // visit(part, owned?)
    std::uint64_t halo = 0;
    visit(parts_of(points, i, halo), true);
    for (; halo; halo &= halo - 1) visit(std::countr_zero(halo), false);
  };
#pragma omp parallel for schedule(static)
  for (int t = 0; t < pieces; ++t) {
    const auto [begin, end] = range(t);
    std::array<std::array<std::size_t, 3>, 64> counts{};  // on the thread's stack: no false sharing
    for (std::size_t i = begin; i < end; ++i)
      each_part_of(i, [&](int p, bool owned) {
        ++counts[p][owned ? 0 : 1];
        ++counts[p][2];
        owner[i] = owned ? static_cast<std::uint8_t>(p) : owner[i] | in_halos;
      });
    std::copy_n(counts.begin(), count, at.begin() + t * count);
  }
  // Exclusive scans over the pieces: where each piece writes in each part's lists.
  for (int p = 0; p < count; ++p) {
    std::array<std::size_t, 3> total{0, 0, 0};
    for (int t = 0; t < pieces; ++t) {
      auto& cursor = at[static_cast<std::size_t>(t * count + p)];
      for (int k = 0; k < 3; ++k) total[k] += std::exchange(cursor[k], total[k]);
    }
    PartLists& part = parts[static_cast<std::size_t>(p)];
    part.owned.resize(total[0]);
    part.halo.resize(local ? 0 : total[1]);
    part.global.resize(local ? total[2] : 0);
    part.owned_rows.resize(local ? total[0] : 0);
    part.halo_count = total[1];
  }
#pragma omp parallel for schedule(static)
  for (int t = 0; t < pieces; ++t) {
    const auto [begin, end] = range(t);
    std::array<std::array<std::size_t, 3>, 64> cursors{};
    std::copy_n(at.begin() + t * count, count, cursors.begin());
    for (std::size_t i = begin; i < end; ++i) {
      auto write = [&](int p, bool owned) {
        PartLists& part = parts[static_cast<std::size_t>(p)];
        auto& cursor = cursors[p];
        const auto id = static_cast<point_id>(i);
        if (local) {
          if (owned) part.owned_rows[cursor[0]] = static_cast<point_id>(cursor[2]);
          part.global[cursor[2]++] = id;
        }
        if (owned) part.owned[cursor[0]++] = id;
        else if (!local) part.halo[cursor[1]++] = id;
      };
      if (owner[i] & in_halos) each_part_of(i, write);
      else write(owner[i], true);
    }
  }
  return parts;
}

}  // namespace horizon::detail
