// Bond filters (issue 12): where the filter's time goes, in one process. Lattice 100, m = 3.015,
// bench/filters/ten_cracks.json. Per round: the open search (grid + search, pools reused), the
// filter of its list, and the filter's move of rows alone (move_rows_down on a copy of the open
// list with the filtered list's offsets), and a parallel copy of the list (bandwidth floor).
// Usage: filter_phases THREADS [FILTERS.json]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <sys/resource.h>

#include "core/select_entries.hpp"
#include "horizon/bond_filter.hpp"
#include "horizon/generate.hpp"
#include "horizon/io.hpp"
#include "horizon/search.hpp"
using namespace horizon;

static double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
static double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int main(int argc, char** argv) {
  const int threads = argc > 1 ? atoi(argv[1]) : 1;
  const char* json = argc > 2 ? argv[2] : "bench/filters/ten_cracks.json";
  PointSet points = lattice(100, 3, 10.0);
  SearchOptions o;
  o.horizon = 0.3015;
  o.backend = Backend::openmp;
  o.threads = threads;
  const std::vector<BondFilter> filters = read_bond_filters(json);
  std::vector<double> s, f, m, c;
  for (int r = 0; r < 7; ++r) {
    SearchStats stats;
    NeighborList list = search(points.view(), o, &stats);
    s.push_back(stats.grid_seconds + stats.search_seconds);
    Buffer<point_id> copy(list.indices().size());
    double t0 = now();
#pragma omp parallel for num_threads(threads)
    for (std::int64_t b = 0; b < std::int64_t(copy.size() >> 16) + 1; ++b) {
      const std::size_t begin = std::size_t(b) << 16, end = std::min(copy.size(), begin + (std::size_t{1} << 16));
      if (begin < end) std::memcpy(copy.data() + begin, list.indices().data() + begin, (end - begin) * sizeof(point_id));
    }
    c.push_back(now() - t0);
    const Buffer<std::int64_t> old_offsets = list.offsets();
    t0 = now();
    NeighborList kept = filter_bonds(std::move(list), points.view(), filters, o.horizon, threads);
    f.push_back(now() - t0);
    t0 = now();
    detail::move_rows_down(copy.data(), old_offsets.data(), kept.offsets().data(),
                           std::int64_t(old_offsets.size()) - 1, threads);
    m.push_back(now() - t0);
    rusage u;
    getrusage(RUSAGE_SELF, &u);
    fprintf(stderr, "round %d: minor faults so far %ld\n", r, u.ru_minflt);
    if (r == 0) printf("entries %zu -> %zu\n", old_offsets.back() + 0ul, kept.indices().size() + 0ul);
  }
  printf("threads=%d search %.1f ms, filter %.1f ms (of which moving rows %.1f ms), copy of the list %.1f ms, "
         "(search + filter) / search %.3f\n",
         threads, median(s) * 1e3, median(f) * 1e3, median(m) * 1e3, median(c) * 1e3,
         (median(s) + median(f)) / median(s));
}
