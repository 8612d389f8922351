#include <cstdio>
#include <cstdlib>
#include <cstring>
#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "horizon/buffer.hpp"
using namespace horizon;
// One kind of search (open or periodic box), repeated: for perf sample counts per symbol.
int main(int argc, char** argv) {
  const bool periodic = argc > 1 && !strcmp(argv[1], "periodic");
  const double m = argc > 2 ? atof(argv[2]) : 1.5;
  PointSet points = lattice(100, 3, 10.0);
  SearchOptions o; o.horizon = m * 0.1; o.backend = Backend::serial;
  if (periodic) o.box = {10, 10, 10};
  double grid = 0, search_s = 0;
  for (int r = 0; r < 12; ++r) {
    SearchStats s;
    const auto total = horizon::search(points.view(), o, &s).total();
    if (r >= 2) grid += s.grid_seconds, search_s += s.search_seconds;
    printf("  call %d grid %.2f ms held %.1f MB\n", r, s.grid_seconds * 1e3, horizon::detail::cached_buffer_bytes() / 1e6);
    if (r == 0) printf("%s m=%g entries %lld\n", periodic ? "periodic" : "open", m, (long long)total);
  }
  printf("mean of 10: grid %.2f ms, search %.2f ms\n", grid / 10 * 1e3, search_s / 10 * 1e3);
}
