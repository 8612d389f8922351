#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>
using clk = std::chrono::steady_clock;
int main(int argc, char** argv) {
  const int n = 1000000; bool shuffled = argv[1][0] == 's';
  std::vector<int> order(n); std::iota(order.begin(), order.end(), 0);
  // simulate cell order: for lattice order, cells group nearby ids; use a block-local shuffle
  std::mt19937_64 rng(7);
  if (shuffled) std::shuffle(order.begin(), order.end(), rng);
  else for (int b = 0; b < n; b += 64) std::shuffle(order.begin() + b, order.begin() + std::min(n, b + 64), rng);
  std::vector<int> rank(n); for (int p = 0; p < n; ++p) rank[order[p]] = p;
  std::vector<double> xyz(3 * n); for (int i = 0; i < 3 * n; ++i) xyz[i] = i;
  std::vector<double> sx(n), sy(n), sz(n);
  struct Item { int p; double x, y, z; };
  const int shift = 12; const int buckets = (n >> shift) + 1;
  std::vector<Item> tmp(n); std::vector<int> start(buckets + 1);
  for (int rep = 0; rep < 5; ++rep) {
    auto t0 = clk::now();
    for (int p = 0; p < n; ++p) {
      if (p + 16 < n) __builtin_prefetch(&xyz[3 * (size_t)order[p + 16]]);
      const size_t i = order[p]; sx[p] = xyz[3 * i]; sy[p] = xyz[3 * i + 1]; sz[p] = xyz[3 * i + 2];
    }
    auto t1 = clk::now();
    for (int i = 0; i < n; ++i) { const int p = rank[i]; sx[p] = xyz[3 * (size_t)i]; sy[p] = xyz[3 * (size_t)i + 1]; sz[p] = xyz[3 * (size_t)i + 2]; }
    auto t2 = clk::now();
    std::fill(start.begin(), start.end(), 0);
    for (int i = 0; i < n; ++i) ++start[(rank[i] >> shift) + 1];
    for (int b = 0; b < buckets; ++b) start[b + 1] += start[b];
    std::vector<int> next(start.begin(), start.end() - 1);
    for (int i = 0; i < n; ++i) { const int p = rank[i]; tmp[next[p >> shift]++] = {p, xyz[3 * (size_t)i], xyz[3 * (size_t)i + 1], xyz[3 * (size_t)i + 2]}; }
    for (int k = 0; k < n; ++k) { const Item& it = tmp[k]; sx[it.p] = it.x; sy[it.p] = it.y; sz[it.p] = it.z; }
    auto t3 = clk::now();
    auto ms = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count() * 1e3; };
    printf("%s gather %.1f scatter %.1f bucketed %.1f ms\n", argv[1], ms(t0, t1), ms(t1, t2), ms(t2, t3));
  }
}
