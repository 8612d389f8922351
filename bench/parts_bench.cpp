// horizon_parts_bench: the thesis's Table 5.2 predicted on one GPU. Each lattice problem of
// DESIGN.md (n^3 points, horizon m spacings) is cut into p parts exactly as the multi-GPU search
// cuts it (cut_into_parts), and each part is searched alone on the one GPU:
//   device-resident: its search and the move of its own rows to global ids (search_device_part),
//     against one GPU's search_device of the whole problem (points already on the GPU);
//     predicted speed-up = one GPU / the slowest part;
//   host->host: the part's upload, search and copy of its rows to the host, against one GPU's
//     search(); the model adds the cut and bounds the assembly below by the host's own memory:
//     faulting in and writing the list (bandwidth measured here, all cores).
// Then the calls themselves with p parts on the one GPU (devices = {0, 0, ...}): host->host
// search() and device-resident search_device_parts, against their one-part calls; parts on one
// GPU run one after another in effect, so the target is their sum: the one-part call times 1 +
// the halo's share, within 20 %. Prints CSV (each multi-part call's phases on stderr).
#include <CLI/CLI.hpp>
#include <cuda_runtime.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "horizon/cuda.hpp"
#include "horizon/generate.hpp"
#include "horizon/parts.hpp"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"
#include "median_seconds.hpp"

namespace {

using namespace horizon;

void check(cudaError_t status, const char* what) {
  if (status != cudaSuccess) throw Error(std::string(what) + ": " + cudaGetErrorString(status));
}

/// Bytes per second at which all cores fault in and write fresh memory (the best of 3, 2 GiB).
double fault_write_bandwidth() {
  const std::size_t bytes = std::size_t{2} << 30;
  double best = 1e30;
  for (int r = 0; r < 3; ++r) {
    std::unique_ptr<char[]> fresh(new char[bytes]);
    Stopwatch clock;
    const auto chunks = static_cast<std::int64_t>(bytes >> 21);
#pragma omp parallel for schedule(static)
    for (std::int64_t c = 0; c < chunks; ++c) std::memset(fresh.get() + (c << 21), 1, std::size_t{1} << 21);
    best = std::min(best, clock.lap());
  }
  return static_cast<double>(bytes) / best;
}

constexpr double not_run = std::numeric_limits<double>::quiet_NaN();

/// The median of `reps` calls of f, or NaN when the GPU's memory cannot hold it.
template <class F>
double median_or_nan(int reps, F f) {
  try {
    return median_seconds(reps, f);
  } catch (const DeviceOutOfMemory& e) {
    std::fprintf(stderr, "  does not fit: %s\n", e.what());
    return not_run;
  }
}

void print_phases(const char* what, const SearchStats& stats) {
  std::fprintf(stderr, "  %s: partition %.1f ms, assemble %.1f ms, parts", what, stats.partition_seconds * 1e3,
               stats.assemble_seconds * 1e3);
  for (const PartStats& part : stats.parts)
    std::fprintf(stderr, " [%zu+%zu pts %.1f ms, build %.1f ms]", part.owned, part.halo, part.seconds * 1e3,
                 part.build_seconds * 1e3);
  std::fprintf(stderr, "\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"horizon_parts_bench: multi-GPU speed-up predicted from parts timed alone on one GPU, as CSV"};
  std::vector<int> sizes{100, 200, 400}, part_counts{1, 2, 4, 8};
  std::vector<double> spacings{1.5, 3.015};
  int reps = 3, device = 0;
  app.add_option("--sizes", sizes, "lattice points per side")->delimiter(',');
  app.add_option("--m", spacings, "horizons in lattice spacings")->delimiter(',');
  app.add_option("--parts", part_counts, "part counts (1 is always run first)")->delimiter(',');
  app.add_option("--reps", reps, "repetitions of every timing (median)");
  app.add_option("--device", device, "the GPU");
  CLI11_PARSE(app, argc, argv);
  part_counts.erase(std::remove(part_counts.begin(), part_counts.end(), 1), part_counts.end());
  part_counts.insert(part_counts.begin(), 1);

  check(cudaSetDevice(device), "cudaSetDevice");
  warm_up(Backend::cuda);
  const double host_bandwidth = fault_write_bandwidth();
  std::printf("# gpu: %s; cpu threads: %d; host fault-in + write %.1f GB/s\n", cuda_device_name(device).c_str(),
              omp_get_max_threads(), host_bandwidth / 1e9);
  std::printf("n,m,points,entries,parts,halo_share,one_gpu_resident_s,max_part_resident_s,predicted_speedup_resident,"
              "one_gpu_host_s,host_floor_s,predicted_host_s,predicted_speedup_host,"
              "one_part_call_resident_s,parts_call_resident_s,parts_call_resident_ratio,"
              "parts_call_host_s,parts_call_host_ratio,first_parts_call_host_s\n");

  for (int n : sizes)
    for (double m : spacings) {
      const PointSet points = lattice(n);
      SearchOptions options;
      options.horizon = m * 10.0 / n;
      options.backend = Backend::cuda;
      options.device = device;
      std::fprintf(stderr, "n=%d m=%g\n", n, m);

      // One GPU: device-resident (points already there) and host->host.
      double* xyz = nullptr;
      check(cudaMalloc(&xyz, points.xyz.size() * sizeof(double)), "cudaMalloc");
      check(cudaMemcpy(xyz, points.xyz.data(), points.xyz.size() * sizeof(double), cudaMemcpyHostToDevice), "h2d");
      std::int64_t entries = 0;
      const double one_resident = median_or_nan(reps, [&] {
        const DeviceNeighborList list = search_device(xyz, points.size(), 3, options);
        check(cudaDeviceSynchronize(), "sync");
        entries = list.total();
      });
      check(cudaFree(xyz), "cudaFree");
      const double one_host = median_seconds(reps, [&] { entries = search(points.view(), options).total(); });
      const double list_bytes = static_cast<double>(entries) * sizeof(point_id) + (points.size() + 1.0) * 8;
      const double host_floor = list_bytes / host_bandwidth;
      double one_part_call = not_run;

      for (int p : part_counts) {
        // Each part alone: its upload, its device-resident build, its rows' copy to the host.
        const std::vector<PointPart> cut = cut_into_parts(points.view(), p, options);
        double max_resident = 0, max_host = 0, max_copy = 0, halo = 0;
        for (const PointPart& part : cut) {
          std::vector<double> build, upload, copy;
          try {
            for (int r = 0; r < reps; ++r) {
              SearchStats stats;
              const DevicePart rows = search_device_part(points.view(), part, options, &stats);
              Stopwatch clock;
              const NeighborList host = rows.rows.to_host(false);
              copy.push_back(clock.lap());
              build.push_back(stats.kernel_seconds);
              upload.push_back(stats.host_to_device_seconds);
            }
            max_resident = std::max(max_resident, median(build));
            max_host = std::max(max_host, median(upload) + median(build));
            max_copy = std::max(max_copy, median(copy));
          } catch (const DeviceOutOfMemory& e) {
            std::fprintf(stderr, "  a part of %d does not fit: %s\n", p, e.what());
            max_resident = max_host = not_run;
          }
          halo += static_cast<double>(part.halo.size());
        }
        const double halo_share = halo / static_cast<double>(points.size());

        // The calls with p parts on this one GPU, and the cut's own time.
        options.devices.assign(static_cast<std::size_t>(p), device);
        SearchStats stats;
        Stopwatch first_clock;
        search(points.view(), options, &stats);
        const double first_call = first_clock.lap();
        if (p > 1) print_phases("first host call", stats);
        const double parts_host = p == 1 ? one_host : median_seconds(reps, [&] { search(points.view(), options, &stats); });
        if (p > 1) print_phases("host call", stats);
        const double parts_resident = median_or_nan(reps, [&] { search_device_parts(points.view(), options, &stats); });
        if (p == 1) one_part_call = parts_resident;
        options.devices.clear();

        const double predicted_host = stats.partition_seconds + max_host + std::max(host_floor, max_copy);
        std::printf("%d,%g,%zu,%lld,%d,%.4f,%.5f,%.5f,%.2f,%.5f,%.5f,%.5f,%.2f,%.5f,%.5f,%.3f,%.5f,%.3f,%.5f\n", n, m,
                    points.size(), static_cast<long long>(entries), p, halo_share, one_resident, max_resident,
                    one_resident / max_resident, one_host, host_floor, predicted_host, one_host / predicted_host,
                    one_part_call, parts_resident, parts_resident / (one_part_call * (1 + halo_share)), parts_host,
                    parts_host / (one_host * (1 + halo_share)), first_call);
        std::fflush(stdout);
      }
    }
}
