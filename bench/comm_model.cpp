// comm_model: the exact ghost traffic of each exchange strategy for p ranks, computed from the
// decomposition alone (no MPI), for p far beyond the cores at hand. For each rank: the bytes
// and messages it sends to give every other rank its ghosts (32 bytes a point: x, y, z, id).
//   halo:   spatial sub-boxes (brick or RCB); a point goes to each partner whose box, widened
//           by the horizon, holds it.
//   thesis: blocks of the input order (thesis §4.3); a point goes to every rank holding points
//           in a cell adjacent to its own (cells of side horizon), plus the all-gather of every
//           rank's occupied cells (24 bytes a cell to each other rank).
// Prints CSV.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <unordered_map>
#include <vector>

#include "horizon/decomposition.hpp"
#include "horizon/generate.hpp"
#include "horizon/grid.hpp"

namespace {

using namespace horizon;

struct Volume {
  std::vector<std::int64_t> bytes, messages;  // per rank
};

Volume halo_volume(const PointSet& points, const Decomposition& d, double reach) {
  const int p = d.ranks();
  Volume v{std::vector<std::int64_t>(p, 0), std::vector<std::int64_t>(p, 0)};
  std::vector<std::vector<int>> partners(static_cast<std::size_t>(p));
  for (int r = 0; r < p; ++r) partners[static_cast<std::size_t>(r)] = d.partners(r, reach);
  std::vector<std::set<int>> talks_to(static_cast<std::size_t>(p));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double* x = &points.xyz[i * 3];
    const int owner = d.owner(x);
    for (int other : partners[static_cast<std::size_t>(owner)])
      if (d.box(other).near(x, 3, reach)) {
        v.bytes[static_cast<std::size_t>(owner)] += 32;
        talks_to[static_cast<std::size_t>(owner)].insert(other);
      }
  }
  for (int r = 0; r < p; ++r) v.messages[static_cast<std::size_t>(r)] = static_cast<std::int64_t>(talks_to[static_cast<std::size_t>(r)].size());
  return v;
}

Volume thesis_volume(const PointSet& points, int p, double horizon) {
  Volume v{std::vector<std::int64_t>(p, 0), std::vector<std::int64_t>(p, 0)};
  const Grid grid = Grid::fit(points.view(), horizon, 1);
  const std::size_t n = points.size();
  auto rank_of = [&](std::size_t i) { return static_cast<int>(i * static_cast<std::size_t>(p) / n); };
  using Cell = std::array<std::int64_t, 3>;
  auto cell_of = [&](std::size_t i) {
    return Cell{grid.cell_of(points.xyz[i * 3], 0), grid.cell_of(points.xyz[i * 3 + 1], 1),
                grid.cell_of(points.xyz[i * 3 + 2], 2)};
  };
  std::map<Cell, std::vector<int>> holders;
  std::vector<std::int64_t> cells_of_rank(static_cast<std::size_t>(p), 0);
  for (std::size_t i = 0; i < n; ++i) {
    auto& h = holders[cell_of(i)];
    if (std::find(h.begin(), h.end(), rank_of(i)) == h.end()) {
      h.push_back(rank_of(i));
      ++cells_of_rank[static_cast<std::size_t>(rank_of(i))];
    }
  }
  std::vector<std::set<int>> talks_to(static_cast<std::size_t>(p));
  for (std::size_t i = 0; i < n; ++i) {
    const int me = rank_of(i);
    const Cell c = cell_of(i);
    std::set<int> to;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = holders.find(Cell{c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == holders.end()) continue;
          for (int r : it->second)
            if (r != me) to.insert(r);
        }
    v.bytes[static_cast<std::size_t>(me)] += 32 * static_cast<std::int64_t>(to.size());
    talks_to[static_cast<std::size_t>(me)].insert(to.begin(), to.end());
  }
  for (int r = 0; r < p; ++r) {
    // The all-gather of occupied cells reaches every other rank.
    v.bytes[static_cast<std::size_t>(r)] += 24 * cells_of_rank[static_cast<std::size_t>(r)] * (p - 1);
    v.messages[static_cast<std::size_t>(r)] = (p - 1) + static_cast<std::int64_t>(talks_to[static_cast<std::size_t>(r)].size());
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"comm_model: exact ghost traffic per rank for each exchange strategy, as CSV"};
  std::vector<int> sizes{80};
  std::vector<double> spacings{1.5, 3.015};
  int max_ranks = 4096;
  app.add_option("--sizes", sizes, "lattice points per side")->delimiter(',');
  app.add_option("--m", spacings, "horizons in lattice spacings")->delimiter(',');
  app.add_option("--max-ranks", max_ranks, "largest rank count (powers of two)");
  CLI11_PARSE(app, argc, argv);

  std::printf("strategy,n,points,m,ranks,total_bytes,max_rank_bytes,mean_rank_bytes,total_messages,max_rank_messages\n");
  for (int n : sizes)
    for (double m : spacings) {
      const PointSet points = lattice(n);
      const double horizon = m * 10.0 / n;
      const Bounds box = bounds_of(points.view());
      for (int p = 1; p <= max_ranks; p *= 2) {
        auto row = [&](const char* name, const Volume& v) {
          std::int64_t total = 0, most = 0, messages = 0, most_messages = 0;
          for (int r = 0; r < p; ++r) {
            total += v.bytes[static_cast<std::size_t>(r)];
            most = std::max(most, v.bytes[static_cast<std::size_t>(r)]);
            messages += v.messages[static_cast<std::size_t>(r)];
            most_messages = std::max(most_messages, v.messages[static_cast<std::size_t>(r)]);
          }
          std::printf("%s,%d,%zu,%g,%d,%lld,%lld,%.1f,%lld,%lld\n", name, n, points.size(), m, p,
                      static_cast<long long>(total), static_cast<long long>(most), static_cast<double>(total) / p,
                      static_cast<long long>(messages), static_cast<long long>(most_messages));
          std::fflush(stdout);
        };
        row("halo_brick", halo_volume(points, Decomposition::brick(box, 3, p), horizon));
        row("halo_rcb", halo_volume(points, Decomposition::rcb(box, points.view(), p), horizon));
        if (p <= 1024) row("thesis", thesis_volume(points, p, horizon));
      }
    }
  return 0;
}
