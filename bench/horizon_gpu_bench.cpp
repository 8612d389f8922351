// horizon_gpu_bench: the thesis's GPU problems (Table 5.1) on one GPU. For each problem: the
// device-resident time (points on the GPU -> CSR on the GPU: the first call, the median of the
// repeats, and a repeat on the points moved slightly, as a solver's next step), the naive GPU
// cell list on the same points in the same process (bench/naive_gpu_cell_list.cu), the
// host->host time (a first call into fresh memory, the second call, which page-locks the
// pool's blocks, and the median of repeats), the same list from openmp on all CPU cores (the thesis's relative
// throughput, Fig. 5.1), and the floors measured in the same run: PCIe copies of points in and
// list out, and the device write of the list. Prints CSV (each host call's phases on stderr).
#include <CLI/CLI.hpp>
#include <cuda_runtime.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "horizon/cuda.hpp"
#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"
#include "median_seconds.hpp"
#include "naive_gpu_cell_list.hpp"

namespace {

using namespace horizon;

void check(cudaError_t status, const char* what) {
  if (status != cudaSuccess) throw Error(std::string(what) + ": " + cudaGetErrorString(status));
}

struct Bandwidth {
  double host_to_device, device_to_host, device_write;  // bytes per second
};

// Pinned PCIe bandwidth both ways and device write bandwidth (cudaMemset), 1 GiB each.
Bandwidth measure_bandwidth() {
  const std::size_t bytes = std::size_t{1} << 30;
  void *host, *device;
  check(cudaMallocHost(&host, bytes), "cudaMallocHost");
  check(cudaMalloc(&device, bytes), "cudaMalloc");
  std::memset(host, 1, bytes);
  auto time = [](const std::function<void()>& f) {
    f();
    check(cudaDeviceSynchronize(), "sync");
    double best = 1e30;
    for (int r = 0; r < 3; ++r) {
      Stopwatch clock;
      f();
      check(cudaDeviceSynchronize(), "sync");
      best = std::min(best, clock.lap());
    }
    return best;
  };
  Bandwidth bw;
  bw.host_to_device = bytes / time([&] { check(cudaMemcpy(device, host, bytes, cudaMemcpyHostToDevice), "h2d"); });
  bw.device_to_host = bytes / time([&] { check(cudaMemcpy(host, device, bytes, cudaMemcpyDeviceToHost), "d2h"); });
  bw.device_write = bytes / time([&] { check(cudaMemset(device, 0, bytes), "memset"); });
  cudaFree(device);
  cudaFreeHost(host);
  return bw;
}


}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"horizon_gpu_bench: one GPU on the thesis's problems, as CSV"};
  std::vector<int> sizes{50, 100, 150, 200, 250, 300, 350, 400};
  std::vector<double> spacings{1.5, 3.015};
  std::size_t cloud_points = 8000000;
  int reps = 3, cpu_max_n = 400, k = 1;
  bool unsorted = false, host = true;
  app.add_option("--sizes", sizes, "lattice points per side")->delimiter(',');
  app.add_option("--m", spacings, "horizons in lattice spacings")->delimiter(',');
  app.add_option("--cloud-points", cloud_points, "points in the random and clustered clouds (0: none)");
  app.add_option("--reps", reps, "repetitions of the GPU timings (median)");
  app.add_option("--cpu-max-n", cpu_max_n, "largest lattice also timed with openmp");
  app.add_option("--k", k, "cells per horizon");
  app.add_flag("--unsorted", unsorted, "leave rows unsorted");
  app.add_flag("!--no-host", host, "skip the host->host and openmp timings");
  CLI11_PARSE(app, argc, argv);

  const Bandwidth bw = measure_bandwidth();
  std::printf("# gpu: %s; cpu threads: %d; pinned h2d %.1f GB/s, d2h %.1f GB/s, device write %.0f GB/s\n",
              cuda_device_name(0).c_str(), omp_get_max_threads(), bw.host_to_device / 1e9,
              bw.device_to_host / 1e9, bw.device_write / 1e9);
  std::printf("problem,n,points,m,neighbors,device_s,device_points_per_s,device_first_s,device_moved_s,"
              "naive_s,naive_points_per_s,device_vs_naive,device_floor_s,device_vs_floor,"
              "host_s,host_points_per_s,h2d_s,grid_s,kernels_s,d2h_s,copy_floor_s,host_vs_copy_floor,"
              "openmp_s,openmp_points_per_s,gpu_vs_openmp,peak_gpu_gib,host_first_s,host_first_vs_copy_floor,host_second_s\n");

  struct Problem {
    std::string name;
    int n;
    double m;
    PointSet points;
    double horizon;
  };
  std::vector<std::function<Problem()>> problems;
  for (int n : sizes)
    for (double m : spacings) problems.push_back([=] { return Problem{"lattice", n, m, lattice(n), m * 10.0 / n}; });
  if (cloud_points > 0)
    for (double m : spacings) {
      const double h = 10.0 / std::cbrt(static_cast<double>(cloud_points));
      problems.push_back([=] { return Problem{"random", 0, m, random_cloud(cloud_points, 3, 1), m * h}; });
      problems.push_back([=] { return Problem{"clustered", 0, m, clustered_cloud(cloud_points, 64, 1.0, 3, 2), m * h}; });
    }

  for (const auto& make : problems) {
    const Problem p = make();
    const double n_points = static_cast<double>(p.points.size());
    SearchOptions options;
    options.horizon = p.horizon;
    options.backend = Backend::cuda;
    options.cells_per_horizon = k;
    options.sort_rows = !unsorted;

    // Device-resident: points already on the GPU, list left on the GPU. The first call, then
    // the repeats (median), then the points moved by up to 1 % of the horizon.
    const std::size_t values = p.points.xyz.size();
    double* device_xyz = nullptr;
    check(cudaMalloc(&device_xyz, values * sizeof(double)), "cudaMalloc points");
    check(cudaMemcpy(device_xyz, p.points.xyz.data(), values * sizeof(double), cudaMemcpyHostToDevice), "copy points");
    std::vector<double> device_times;
    double device_first = 0, device_moved = 0;
    std::int64_t neighbors = 0;
    std::size_t peak = 0;
    bool device_fits = true;
    auto device_search = [&](bool moved) {
      SearchStats stats;
      Stopwatch clock;
      const DeviceNeighborList list = search_device(device_xyz, p.points.size(), 3, options, nullptr, &stats);
      check(cudaDeviceSynchronize(), "sync");
      const double seconds = clock.lap();
      if (!moved) neighbors = list.total();
      peak = stats.peak_gpu_bytes;
      return seconds;
    };
    try {
      device_first = device_search(false);
      for (int r = 0; r < reps; ++r) device_times.push_back(device_search(false));
      std::vector<double> moved = p.points.xyz;
      for (std::size_t i = 0; i < values; ++i) moved[i] += 0.01 * p.horizon * std::sin(static_cast<double>(i));
      check(cudaMemcpy(device_xyz, moved.data(), values * sizeof(double), cudaMemcpyHostToDevice), "copy points");
      device_moved = device_search(true);
      check(cudaMemcpy(device_xyz, p.points.xyz.data(), values * sizeof(double), cudaMemcpyHostToDevice), "copy points");
    } catch (const DeviceOutOfMemory& e) {
      device_fits = false;
      std::fprintf(stderr, "device-resident n=%d m=%g: %s\n", p.n, p.m, e.what());
    }
    // The naive kernel on the same points (k = 1, Euclidean, full lists, unsorted rows).
    std::vector<double> naive_times;
    for (int r = 0; r < reps + 1 && device_fits && k == 1; ++r) {
      const bench::NaiveGpuResult naive = bench::naive_gpu_cell_list(device_xyz, p.points.size(), p.horizon);
      if (r > 0) naive_times.push_back(naive.seconds);  // the first run warms up
      if (naive.entries != neighbors)
        std::fprintf(stderr, "MISMATCH: naive %lld vs horizon %lld\n", static_cast<long long>(naive.entries),
                     static_cast<long long>(neighbors));
    }
    cudaFree(device_xyz);

    // Host -> host: a first call into fresh memory, then the median of repeated calls (each
    // list freed before the next, as by a solver searching every step), with its phases.
    std::vector<std::pair<double, SearchStats>> host_runs;
    double host_first = 0, host_second = 0;  // the second call page-locks the pool's blocks
    release_cached_buffers();
    for (int r = 0; r < (host ? reps + 1 : 0); ++r) {
      SearchStats stats;
      Stopwatch clock;
      const NeighborList list = search(p.points.view(), options, &stats);
      const double call = clock.lap();
      if (r == 0) host_first = call;
      else host_runs.emplace_back(call, stats);
      if (r == 1) host_second = call;
      // Every call's phases, for the outliers a median hides.
      std::fprintf(stderr, "host %s %d m=%g call %d: %.1f ms (h2d %.1f, grid %.1f, kernels %.1f, d2h %.1f)\n",
                   p.name.c_str(), p.n, p.m, r, call * 1e3, stats.host_to_device_seconds * 1e3,
                   stats.grid_seconds * 1e3, stats.kernel_seconds * 1e3, stats.device_to_host_seconds * 1e3);
      neighbors = list.total();
      peak = std::max(peak, stats.peak_gpu_bytes);
    }
    std::sort(host_runs.begin(), host_runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const double host_s = host ? host_runs[host_runs.size() / 2].first : 0.0;
    const SearchStats host_stats = host ? host_runs[host_runs.size() / 2].second : SearchStats{};
    const double list_bytes = static_cast<double>(neighbors) * 4 + (n_points + 1) * 8;
    const double copy_floor = n_points * 24 / bw.host_to_device + list_bytes / bw.device_to_host;
    const double device_s = device_fits ? median(device_times) : 0.0;
    const double naive_s = naive_times.empty() ? 0.0 : median(naive_times);
    const double device_floor = list_bytes / bw.device_write;

    // openmp on every core of the GPU's host.
    double openmp_s = 0;
    if (host && p.n <= cpu_max_n) {
      SearchOptions cpu = options;
      cpu.backend = Backend::openmp;
      Stopwatch clock;
      const NeighborList list = search(p.points.view(), cpu);
      openmp_s = clock.lap();
      if (list.total() != neighbors) std::fprintf(stderr, "MISMATCH: openmp %lld vs cuda %lld\n",
                                                  static_cast<long long>(list.total()), static_cast<long long>(neighbors));
    }
    std::printf("%s,%d,%zu,%g,%lld,%.5f,%.4g,%.5f,%.5f,%.5f,%.4g,%.2f,%.5f,%.2f,%.4f,%.4g,%.4f,%.4f,%.4f,%.4f,%.4f,%.2f,%.4f,%.4g,%.1f,%.2f,%.4f,%.2f,%.4f\n",
                p.name.c_str(), p.n, p.points.size(), p.m, static_cast<long long>(neighbors), device_s,
                device_s > 0 ? n_points / device_s : 0.0, device_first, device_moved, naive_s,
                naive_s > 0 ? n_points / naive_s : 0.0, device_s > 0 && naive_s > 0 ? naive_s / device_s : 0.0,
                device_floor, device_s > 0 ? device_s / device_floor : 0.0,
                host_s, host_s > 0 ? n_points / host_s : 0.0, host_stats.host_to_device_seconds, host_stats.grid_seconds,
                host_stats.kernel_seconds,
                host_stats.device_to_host_seconds, copy_floor, host_s > 0 ? host_s / copy_floor : 0.0, openmp_s,
                openmp_s > 0 ? n_points / openmp_s : 0.0, openmp_s > 0 ? openmp_s / host_s : 0.0,
                static_cast<double>(peak) / (1 << 30), host_first, host_first / copy_floor, host_second);
    std::fflush(stdout);
  }
  return 0;
}
