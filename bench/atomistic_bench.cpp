// horizon_atomistic_bench: atomistic systems against vesin (Luthaf/vesin, built from a local copy
// by this directory's CMake) in one process, on the same atoms: rattled diamond supercells of 64
// to 10^6 atoms at 5 and 6 angstrom, the same atoms in a triclinic cell of the same volume, the
// 10^6-point lattice and cloud of the other benchmarks in a periodic cube, and primitive cells
// with cutoffs 2-5x the cell; one core and all; ids only, and with distances and
// vectors, rows sorted and not (vesin: the same, full list, unsorted). With a GPU, a row per system for the GPU:
// horizon's device-resident search (search_device) against vesin's CUDA path, atoms, cell and
// lists in GPU memory, each call timed to its end on the GPU. CSV with the ratios.
#include <CLI/CLI.hpp>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "horizon/cuda.hpp"
#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "median_seconds.hpp"
#if defined(HORIZON_WITH_VESIN)
#include "vesin.h"
#endif
#if defined(HORIZON_WITH_CUDA)
#include <cuda_runtime.h>
#endif

using namespace horizon;

namespace {

struct System {
  std::string name;
  std::vector<double> xyz;  // N x 3
  Cell cell;
  double cutoff;
};

/// Diamond silicon, k x k x k cubic cells (8 k^3 atoms), rattled by 0.05 angstrom; with `skew`
/// the same fractional positions in a triclinic cell of the same volume.
System diamond(int k, double cutoff, bool skew) {
  const double a = 5.43, side = a * k;
  const double basis[8][3] = {{0, 0, 0},       {0, .5, .5},     {.5, 0, .5},     {.5, .5, 0},
                              {.25, .25, .25}, {.25, .75, .75}, {.75, .25, .75}, {.75, .75, .25}};
  System s;
  s.name = std::string(skew ? "diamond_triclinic_" : "diamond_") + std::to_string(8 * k * k * k);
  s.cutoff = cutoff;
  s.cell.vectors = {{{side, 0, 0}, {skew ? 0.3 * side : 0, side, 0}, {skew ? 0.2 * side : 0, skew ? 0.25 * side : 0, side}}};
  s.cell.pbc = {true, true, true};
  std::mt19937_64 rng(8);
  std::normal_distribution<double> rattle(0, 0.05);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l)
        for (const auto& b : basis) {
          const double f[3] = {(i + b[0]) / k, (j + b[1]) / k, (l + b[2]) / k};
          for (int c = 0; c < 3; ++c)
            s.xyz.push_back(f[0] * s.cell.vectors[0][c] + f[1] * s.cell.vectors[1][c] + f[2] * s.cell.vectors[2][c] +
                            rattle(rng));
        }
  return s;
}

/// A primitive cell: fcc copper (1 atom) or diamond silicon (2 atoms), with the cutoff given.
System primitive(bool silicon, double cutoff) {
  const double a = silicon ? 5.43 : 3.61;
  System s;
  s.name = std::string(silicon ? "si_primitive_" : "cu_primitive_") + std::to_string(static_cast<int>(cutoff)) + "A";
  s.cutoff = cutoff;
  s.cell.vectors = {{{0, a / 2, a / 2}, {a / 2, 0, a / 2}, {a / 2, a / 2, 0}}};
  s.cell.pbc = {true, true, true};
  s.xyz = {0, 0, 0};
  if (silicon) s.xyz.insert(s.xyz.end(), {a / 4, a / 4, a / 4});
  return s;
}

/// The 10^6-point problems of the other benchmarks in a periodic cube of side 10: the lattice
/// (spacing 0.1) or a random cloud, at m = 1.5 or 3.015 spacings.
System cube(bool cloud, double m) {
  System s;
  s.name = std::string(cloud ? "cloud_" : "lattice_") + "1000000_m" + (m < 2 ? "1.5" : "3.015");
  s.cutoff = m * 0.1;
  s.cell = Cell::orthorhombic({10, 10, 10});
  s.xyz = (cloud ? random_cloud(1000000, 3, 1, 10.0) : lattice(100, 3, 10.0)).xyz;
  return s;
}

#if defined(HORIZON_WITH_VESIN)
/// vesin's options for a full, unsorted list, with shifts, distances and vectors when asked.
VesinOptions vesin_options(const System& s, bool geometry, int threads) {
  VesinOptions options{};
  options.cutoff = s.cutoff;
  options.full = true;
  options.sorted = false;
  options.algorithm = VesinAutoAlgorithm;
  options.n_threads = threads;
  options.return_shifts = geometry;
  options.return_distances = geometry;
  options.return_vectors = geometry;
  return options;
}

/// vesin's full list with shifts, distances and vectors when asked, `threads` threads.
std::size_t run_vesin(const System& s, bool geometry, int threads) {
  const VesinOptions options = vesin_options(s, geometry, threads);
  VesinNeighborList list;
  const char* error = nullptr;
  const bool periodic[3] = {s.cell.pbc[0], s.cell.pbc[1], s.cell.pbc[2]};
  const int status = vesin_neighbors(reinterpret_cast<const double(*)[3]>(s.xyz.data()), s.xyz.size() / 3,
                                     reinterpret_cast<const double(*)[3]>(s.cell.vectors.data()),
                                     periodic, {VesinCPU, 0}, options, &list, &error);
  if (status != 0) {
    std::fprintf(stderr, "vesin: %s\n", error ? error : "error");
    std::exit(1);
  }
  const std::size_t length = list.length;
  vesin_free(&list);
  return length;
}
#endif

#if defined(HORIZON_WITH_CUDA)
void check(cudaError_t status, const char* what) {
  if (status == cudaSuccess) return;
  std::fprintf(stderr, "%s: %s\n", what, cudaGetErrorString(status));
  std::exit(1);
}

/// The system's atoms, cell and pbc in GPU memory, as both libraries take them there.
struct OnGpu {
  explicit OnGpu(const System& s) {
    check(cudaMalloc(&xyz, s.xyz.size() * sizeof(double)), "cudaMalloc atoms");
    check(cudaMemcpy(xyz, s.xyz.data(), s.xyz.size() * sizeof(double), cudaMemcpyHostToDevice), "atoms");
    check(cudaMalloc(&cell, 9 * sizeof(double)), "cudaMalloc cell");
    check(cudaMemcpy(cell, s.cell.vectors.data(), 9 * sizeof(double), cudaMemcpyHostToDevice), "cell");
    const bool periodic[3] = {s.cell.pbc[0], s.cell.pbc[1], s.cell.pbc[2]};
    check(cudaMalloc(&pbc, sizeof(periodic)), "cudaMalloc pbc");
    check(cudaMemcpy(pbc, periodic, sizeof(periodic), cudaMemcpyHostToDevice), "pbc");
  }
  ~OnGpu() {
    cudaFree(xyz);
    cudaFree(cell);
    cudaFree(pbc);
  }
  double* xyz = nullptr;
  double* cell = nullptr;
  bool* pbc = nullptr;
};

/// horizon's device-resident search, its list left on the GPU; the entries.
std::int64_t run_horizon_gpu(const OnGpu& gpu, std::size_t atoms, const SearchOptions& options) {
  const DeviceNeighborList list = search_device(gpu.xyz, atoms, 3, options);
  check(cudaDeviceSynchronize(), "horizon on the GPU");
  return list.total();
}

#if defined(HORIZON_WITH_VESIN_CUDA)
/// vesin's CUDA path with shifts, distances and vectors, its list (reused from call to call, as
/// vesin intends) left on the GPU; the entries, or -1 when vesin refuses the system.
long long run_vesin_gpu(const OnGpu& gpu, const System& s, VesinNeighborList& list) {
  const VesinOptions options = vesin_options(s, true, 1);
  const char* error = nullptr;
  const int status = vesin_neighbors(reinterpret_cast<const double(*)[3]>(gpu.xyz), s.xyz.size() / 3,
                                     reinterpret_cast<const double(*)[3]>(gpu.cell), gpu.pbc, {VesinCUDA, 0},
                                     options, &list, &error);
  check(cudaDeviceSynchronize(), "vesin on the GPU");
  if (status != 0) {
    std::fprintf(stderr, "# vesin (CUDA), %s: %s\n", s.name.c_str(), error ? error : "error");
    return -1;
  }
  return static_cast<long long>(list.length);
}
#endif

/// The GPU's row of system s: ids only and S, d, D on horizon's device-resident search, and vesin's CUDA path.
void gpu_row(const System& s, int reps) {
  const OnGpu gpu(s);
  const std::size_t atoms = s.xyz.size() / 3;
  SearchOptions ids;
  ids.horizon = s.cutoff;
  ids.cell = s.cell;
  SearchOptions geometry = ids;
  geometry.outputs = {true, true, true};
  std::int64_t entries = 0;
  run_horizon_gpu(gpu, atoms, geometry);  // warm-up: the context, the pool
  const double ids_s = median_seconds(reps, [&] { entries = run_horizon_gpu(gpu, atoms, ids); });
  const double geometry_s = median_seconds(reps, [&] { entries = run_horizon_gpu(gpu, atoms, geometry); });
  long long vesin_entries = 0;
  double vesin_s = 0;
#if defined(HORIZON_WITH_VESIN_CUDA)
  VesinNeighborList list{};
  if (run_vesin_gpu(gpu, s, list) >= 0)  // warm-up: NVRTC compiles its kernels
    vesin_s = median_seconds(reps, [&] { vesin_entries = run_vesin_gpu(gpu, s, list); });
  vesin_free(&list);
#endif
  // The GPU's rows come sorted at no extra cost: the unsorted columns repeat the sorted ones.
  std::printf("%s,%zu,%g,gpu,%lld,%.6f,%.6f,%.2f,%lld,%.6f,%.2f,%.6f,%.2f\n", s.name.c_str(), atoms, s.cutoff,
              static_cast<long long>(entries), ids_s, geometry_s, geometry_s / ids_s, vesin_entries, vesin_s,
              vesin_s / geometry_s, geometry_s, vesin_s / geometry_s);
  std::fflush(stdout);
}
#endif

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"horizon_atomistic_bench: atomistic systems, horizon against vesin, as CSV"};
  int reps = 5, largest = 50;
  std::string only;
  app.add_option("--reps", reps, "repetitions (the median is reported)");
  app.add_option("--only", only, "only the systems whose name contains this (diamond, triclinic, lattice, cloud, primitive)");
  app.add_option("--largest", largest, "largest supercell k (8 k^3 atoms; 50: 10^6)");
  bool gpu_only = false;
  app.add_flag("--gpu-only", gpu_only, "only the GPU rows (with a GPU)");
  CLI11_PARSE(app, argc, argv);
  std::vector<System> systems;
  for (int k : {2, 4, 8, 16, 32, 50})
    if (k <= largest)
      for (double cutoff : {5.0, 6.0}) {
        systems.push_back(diamond(k, cutoff, false));
        if (k >= 4) systems.push_back(diamond(k, cutoff, true));
      }
  if (largest >= 50)
    for (bool cloud : {false, true})
      for (double m : {1.5, 3.015}) systems.push_back(cube(cloud, m));
  for (double cutoff : {5.0, 9.0, 12.75}) systems.push_back(primitive(false, cutoff));
  systems.push_back(primitive(true, 5.0));
  const int all = omp_get_max_threads();
#if defined(HORIZON_WITH_VESIN)
  const bool with_vesin = true;
#else
  const bool with_vesin = false;
#endif
  std::printf("# %d hardware threads; median of %d calls after one warm-up; full lists; vesin %s\n", all, reps,
              with_vesin ? "built from its source (sorted = false)" : "not built (give -DHORIZON_VESIN_SOURCE)");
  std::printf("system,atoms,cutoff,threads,entries,ids_s,geometry_s,geometry_over_ids,vesin_entries,vesin_s,"
              "vesin_over_horizon,unsorted_s,vesin_over_unsorted\n");
  for (const System& s : systems) {
    if (s.name.find(only) == std::string::npos) continue;
#if defined(HORIZON_WITH_CUDA)
    if (backend_available(Backend::cuda)) gpu_row(s, reps);
#endif
    for (int threads : {1, all}) {
      if (gpu_only) break;
      if (threads == all && all == 1) continue;
      const PointView points(s.xyz.data(), s.xyz.size() / 3, 3);
      SearchOptions ids;
      ids.horizon = s.cutoff;
      ids.cell = s.cell;
      ids.backend = threads == 1 ? Backend::serial : Backend::openmp;
      ids.threads = threads;
      SearchOptions geometry = ids;
      geometry.outputs = {true, true, true};
      std::int64_t entries = 0;
      search(points, geometry);  // warm-up: pools, threads
      const double ids_s = median_seconds(reps, [&] { entries = search(points, ids).total(); });
      const double geometry_s = median_seconds(reps, [&] { entries = search(points, geometry).total(); });
      SearchOptions unsorted = geometry;  // vesin's contract: rows in no particular order
      unsorted.sort_rows = false;
      const double unsorted_s = median_seconds(reps, [&] { entries = search(points, unsorted).total(); });
      double vesin_s = 0;
      std::size_t vesin_entries = 0;
#if defined(HORIZON_WITH_VESIN)
      run_vesin(s, true, threads);
      vesin_s = median_seconds(reps, [&] { vesin_entries = run_vesin(s, true, threads); });
#endif
      std::printf("%s,%zu,%g,%d,%lld,%.6f,%.6f,%.2f,%zu,%.6f,%.2f,%.6f,%.2f\n", s.name.c_str(), points.size(), s.cutoff,
                  threads, static_cast<long long>(entries), ids_s, geometry_s, geometry_s / ids_s, vesin_entries,
                  vesin_s, with_vesin ? vesin_s / geometry_s : 0.0, unsorted_s, with_vesin ? vesin_s / unsorted_s : 0.0);
      std::fflush(stdout);
    }
  }
}
