#include <hwy/highway.h>
#include "core/sort_network-inl.h"
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>
#include <algorithm>
namespace hn = hwy::HWY_NAMESPACE;
int main(int argc, char** argv) {
  const int len = argc > 1 ? atoi(argv[1]) : 19;
  const int rows = 1 << 20;
  std::vector<int> in(size_t(rows) * len + 64), out(size_t(rows) * len + 64);
  std::mt19937 g(1);
  for (auto& v : in) v = int(g() % 1000000);
  double best = 1e9;
  for (int rep = 0; rep < 7; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < rows; ++r) {
      const int* row = in.data() + size_t(r) * len;
      int* place = out.data() + size_t(r) * len;
      if (horizon::detail::HWY_NAMESPACE::SortShortRowTo(row, len, -1, place, len)) continue;
      std::copy(row, row + len, place);  // longer rows: the insertion sort they took before
      for (int i = 1; i < len; ++i)
        for (int j = i; j > 0 && place[j - 1] > place[j]; --j) std::swap(place[j - 1], place[j]);
    }
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  for (int r = 0; r < rows; ++r) {
    std::vector<int> e(in.begin() + size_t(r) * len, in.begin() + size_t(r + 1) * len); std::sort(e.begin(), e.end());
    if (!std::equal(e.begin(), e.end(), out.begin() + size_t(r) * len)) { printf("WRONG row %d\n", r); return 1; }
  }
  printf("%s len %d: %.1f ns/row\n", hwy::TargetName(HWY_TARGET), len, best / rows * 1e9);
}
