#include <horizon/generate.hpp>
#include <horizon/search.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
using namespace horizon;
int main(int argc, char** argv) {
  const std::size_t n = std::atoll(argv[1]);
  const double m = std::atof(argv[2]);
  const bool clustered = argv[3][0] == 'c';
  PointSet p = clustered ? clustered_cloud(n, 64, 1.0, 3, 2) : random_cloud(n, 3, 1);
  const double h = 10.0 / std::cbrt(double(n));
  for (int k = 1; k <= 3; ++k) {
    SearchOptions o; o.horizon = m * h; o.cells_per_horizon = k; o.backend = Backend::serial;
    for (int r = 0; r < 2; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      auto list = search(p.view(), o);
      double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (r) std::printf("%s m=%.3f k=%d: %.3f s, %lld entries\n", argv[3], m, k, s, (long long)list.indices().size());
    }
  }
}
