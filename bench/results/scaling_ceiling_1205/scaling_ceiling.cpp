// What 16 threads can give at best on a machine: (1) compute — every thread runs the same
// chain of dependent multiply-adds, so T threads ideally take the time of one (all-core clocks
// lower than one core's turbo show as less than T×); (2) memory — a triad a[i] = b[i] + s*c[i]
// over 3 × 128 MB, GB/s on 1 and on T threads. Prints the speed-up each allows.
// build: g++ -O2 -fopenmp scaling_ceiling.cpp -o scaling_ceiling; usage: scaling_ceiling THREADS
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

double compute_seconds(int threads) {
  constexpr long steps = 200'000'000;
  std::vector<double> sink(static_cast<std::size_t>(threads) * 8);
  const double start = omp_get_wtime();
#pragma omp parallel num_threads(threads)
  {
    double x0 = 1.0 + omp_get_thread_num(), x1 = x0 + 0.5, x2 = x0 + 0.25, x3 = x0 + 0.125;
    for (long s = 0; s < steps; ++s) {  // four independent chains keep one core's FP units busy
      x0 = x0 * 0.999999 + 1e-7;
      x1 = x1 * 0.999999 + 1e-7;
      x2 = x2 * 0.999999 + 1e-7;
      x3 = x3 * 0.999999 + 1e-7;
    }
    sink[static_cast<std::size_t>(omp_get_thread_num()) * 8] = x0 + x1 + x2 + x3;
  }
  const double seconds = omp_get_wtime() - start;
  if (sink[0] == 42) std::printf("-");
  return seconds;
}

double triad_gbs(int threads, std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c) {
  const auto n = static_cast<long>(a.size());
  double best = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    const double start = omp_get_wtime();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) a[i] = b[i] + 1.5 * c[i];
    best = std::min(best, omp_get_wtime() - start);
  }
  return 3.0 * 8.0 * static_cast<double>(n) / best / 1e9;  // bytes read and written (no write-allocate counted)
}

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : omp_get_max_threads();
  const long n = 16L << 20;  // 128 MB per array
  std::vector<double> a(n), b(n, 1.0), c(n, 2.0);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long i = 0; i < n; ++i) a[i] = 0, b[i] = 1, c[i] = 2;  // pages placed by the threads that use them
  const double one = compute_seconds(1), all = compute_seconds(threads), one_again = compute_seconds(1);
  const double serial = std::min(one, one_again);
  std::printf("compute: 1 thread %.3f s, %d threads each the same work %.3f s: speed-up %.1fx of %d\n", serial, threads,
              all, threads * serial / all, threads);
  const double bw1 = triad_gbs(1, a, b, c), bwt = triad_gbs(threads, a, b, c);
  std::printf("triad: 1 thread %.1f GB/s, %d threads %.1f GB/s: %.1fx\n", bw1, threads, bwt, bwt / bw1);
}
