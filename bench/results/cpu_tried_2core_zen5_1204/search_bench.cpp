// usage: search_bench problem(lattice|random|shuffled) m sorted(0/1) reps [threads]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>
#include "horizon/search.hpp"
#include "horizon/generate.hpp"
using namespace horizon;
int main(int argc, char** argv) {
  const char* problem = argv[1];
  double m = atof(argv[2]);
  bool sorted = atoi(argv[3]);
  int reps = atoi(argv[4]);
  int threads = argc > 5 ? atoi(argv[5]) : 1;
  PointSet p = strcmp(problem, "random") == 0 ? random_cloud(1000000) : lattice(100);
  if (strcmp(problem, "shuffled") == 0) {
    std::vector<std::size_t> perm(p.size()); std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), std::mt19937_64(7));
    PointSet q = p; for (std::size_t i = 0; i < perm.size(); ++i) for (int a = 0; a < 3; ++a) q.xyz[3*i+a] = p.xyz[3*perm[i]+a];
    p = q;
  }
  SearchOptions o; o.horizon = m * 0.1; o.sort_rows = sorted; o.backend = threads == 1 ? Backend::serial : Backend::openmp; o.threads = threads;
  std::vector<double> t; long long total = 0;
  for (int r = 0; r < reps; ++r) { SearchStats s; auto l = search(p.view(), o, &s); t.push_back(s.search_seconds); total = l.total(); }
  std::sort(t.begin(), t.end());
  printf("%s m=%g sorted=%d threads=%d entries=%lld search min %.1f med %.1f ms\n", problem, m, sorted, threads, total, t[0]*1e3, t[t.size()/2]*1e3);
}
