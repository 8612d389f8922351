// horizon_device_verlet_bench: the device Verlet list's refresh() against a fresh search_device
// of the same moved points, all on the GPU (lattice n, m = 1.5 and 3.015, skin = 0.1 horizon,
// every point moved by up to a fifth of the skin), checked equal; CSV with the ratio.
#include <CLI/CLI.hpp>
#include <cuda_runtime.h>

#include <cstdio>
#include <random>

#include "horizon/device_verlet_list.hpp"
#include "horizon/generate.hpp"
#include "median_seconds.hpp"

using namespace horizon;

int main(int argc, char** argv) {
  CLI::App app{"horizon_device_verlet_bench: device Verlet refresh against a fresh device search, as CSV"};
  std::vector<int> sizes{100, 200};
  int reps = 5;
  double skin_fraction = 0.1;
  app.add_option("--sizes", sizes, "lattice points per side");
  app.add_option("--reps", reps, "repetitions (the median is reported)");
  app.add_option("--skin", skin_fraction, "skin as a fraction of the horizon");
  CLI11_PARSE(app, argc, argv);
  std::printf("# %s; skin %.3g horizon, points moved by up to skin / 5, device-resident\n",
              cuda_device_name(0).c_str(), skin_fraction);
  std::printf("n,points,m,entries,candidates,build_s,fresh_search_s,refresh_s,needs_rebuild_s,fresh_over_refresh\n");
  cudaStream_t stream;
  cudaStreamCreate(&stream);
  for (int n : sizes)
    for (double m : {1.5, 3.015}) {
      const PointSet points = lattice(n, 3);
      SearchOptions options;
      options.horizon = m * 10.0 / n;
      const double skin = skin_fraction * options.horizon;
      PointSet now = points;
      std::mt19937_64 rng(1);
      std::uniform_real_distribution<double> step(-skin / 5 / 3, skin / 5 / 3);  // |d| < skin / 5
      for (double& x : now.xyz) x += step(rng);
      const std::size_t bytes = points.xyz.size() * sizeof(double);
      double *built = nullptr, *moved = nullptr;
      cudaMalloc(&built, bytes);
      cudaMalloc(&moved, bytes);
      cudaMemcpy(built, points.xyz.data(), bytes, cudaMemcpyHostToDevice);
      cudaMemcpy(moved, now.xyz.data(), bytes, cudaMemcpyHostToDevice);
      auto synced = [&](auto f) { return [&, f] { f(); cudaStreamSynchronize(stream); }; };
      Stopwatch clock;
      const DeviceVerletList verlet(built, points.size(), 3, options, skin, stream);
      cudaStreamSynchronize(stream);
      const double build = clock.lap();
      DeviceNeighborList fresh, refreshed;
      const double search_s = median_seconds(reps, synced([&] { fresh = search_device(moved, now.size(), 3, options, stream); }));
      const double refresh_s = median_seconds(reps, synced([&] { refreshed = verlet.refresh(moved); }));
      bool rebuild = false;
      const double check_s = median_seconds(reps, [&] { rebuild = verlet.needs_rebuild(moved); });
      if (rebuild || !(fresh.to_host(false) == refreshed.to_host(false))) {
        std::fprintf(stderr, "refresh differs from a fresh search (or a rebuild was asked for)\n");
        return 1;
      }
      std::printf("%d,%zu,%g,%lld,%lld,%.5f,%.5f,%.5f,%.5f,%.2f\n", n, points.size(), m,
                  static_cast<long long>(fresh.total()), static_cast<long long>(verlet.candidates().total()), build,
                  search_s, refresh_s, check_s, search_s / refresh_s);
      fresh = DeviceNeighborList();
      refreshed = DeviceNeighborList();
      cudaFree(built);
      cudaFree(moved);
    }
  cudaStreamDestroy(stream);
  return 0;
}
