#include "core/select_entries.hpp"
#include <chrono>
#include <cstdio>
#include <random>
using namespace horizon;
int main(int argc, char** argv) {
  int threads = atoi(argv[1]);
  const std::int64_t n = 1000000;
  std::vector<std::int64_t> from(n + 1), to(n + 1);
  std::mt19937_64 rng(1);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t length = 123, kept = (i > n * 47 / 100 && (i % 10) < 4) ? 123 - 25 : 123;
    from[i + 1] = from[i] + length; to[i + 1] = to[i] + kept;
  }
  std::vector<point_id> data(from[n]);
  for (size_t e = 0; e < data.size(); ++e) data[e] = e;
  std::vector<point_id> copy = data;
  for (int r = 0; r < 5; ++r) {
    std::copy(copy.begin(), copy.end(), data.begin());
    auto t0 = std::chrono::steady_clock::now();
    detail::move_rows_down(data.data(), from.data(), to.data(), n, threads);
    auto t1 = std::chrono::steady_clock::now();
    std::memmove(data.data() + to[n * 47 / 100], data.data() + to[n*47/100] + 1000000, (to[n] - to[n * 47 / 100]) * 4);
    auto t2 = std::chrono::steady_clock::now();
    printf("threads %d: move_rows_down %.1f ms, one memmove of the same span (1 thread) %.1f ms\n", threads,
           std::chrono::duration<double>(t1 - t0).count() * 1e3, std::chrono::duration<double>(t2 - t1).count() * 1e3);
  }
}
