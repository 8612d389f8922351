// In-process A/B of select_entries (VerletList::refresh's selection), as run for this folder's
// README: "select_entries.hpp" was the one-pass variant (not committed), the second include
// main's version (7eb38e9) renamed into namespace old_detail. Built with the Release flags
// against libhorizon.a: g++ -O3 -ffp-contract=off -fopenmp -std=c++20 -Iinclude -Isrc/core -Isrc.
#include <chrono>
#include <cstdio>
#include <random>
#include <algorithm>
#include <omp.h>
#include "select_entries.hpp"
#include "/tmp/selab/select_entries_old.hpp"
#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "horizon/metric.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  const int threads = argc > 1 ? atoi(argv[1]) : 1;
  const double m = argc > 2 ? atof(argv[2]) : 3.015;
  const PointSet points = lattice(100, 3);
  SearchOptions o; o.horizon = m * 0.1 * 1.1; o.backend = Backend::openmp; o.threads = 2;
  const NeighborList cand = search(points.view(), o);
  PointSet now = points; std::mt19937_64 rng(1);
  const double skin = 0.1 * m * 0.1;
  std::uniform_real_distribution<double> step(-skin / 15, skin / 15);
  for (double& x : now.xyz) x += step(rng);
  const double limit = (m * 0.1) * (m * 0.1);
  const double* xyz = now.xyz.data();
  auto keep = [&](std::size_t i, point_id j) {
    const double* a = xyz + 3 * i; const double* b = xyz + 3 * static_cast<std::size_t>(j);
    return metric_accumulate<Metric::euclidean>(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < limit;
  };
  std::vector<double> tn, to;
  NeighborList a, b;
  for (int r = 0; r < 9; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    a = detail::select_entries(cand, keep, threads);
    auto t1 = std::chrono::steady_clock::now();
    b = old_detail::select_entries(cand, keep, threads);
    auto t2 = std::chrono::steady_clock::now();
    tn.push_back(std::chrono::duration<double>(t1 - t0).count()); to.push_back(std::chrono::duration<double>(t2 - t1).count());
  }
  std::sort(tn.begin(), tn.end()); std::sort(to.begin(), to.end());
  std::printf("threads %d m %.3f candidates %lld kept %lld equal %d | new min %.4f med %.4f | old min %.4f med %.4f\n", threads, m,
              (long long)cand.total(), (long long)a.total(), int(a == b), tn[0], tn[4], to[0], to[4]);
}
