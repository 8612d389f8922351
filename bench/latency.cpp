#include "latency.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "horizon/generate.hpp"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"
#include "textbook_cell_list.hpp"
#if defined(HORIZON_WITH_VESIN)
#include "vesin.h"
#endif

namespace bench {
namespace {

/// `count` processes that spin until stopped, as other ranks or a build sharing the cores would.
class BusyProcesses {
public:
  explicit BusyProcesses(int count) {
    for (int i = 0; i < count; ++i) {
      const pid_t pid = fork();
      if (pid == 0) {
        volatile unsigned long spin = 0;
        for (;;) spin = spin + 1;
      }
      if (pid > 0) children_.push_back(pid);
    }
    if (count > 0) std::this_thread::sleep_for(std::chrono::milliseconds(200));  // let them take the cores
  }
  ~BusyProcesses() {
    for (pid_t pid : children_) kill(pid, SIGKILL);
    for (pid_t pid : children_) waitpid(pid, nullptr, 0);
  }
  BusyProcesses(const BusyProcesses&) = delete;
  BusyProcesses& operator=(const BusyProcesses&) = delete;

private:
  std::vector<pid_t> children_;
};

struct Calls {
  double first_us = 0;
  std::vector<double> us;  // every call after the first, sorted
};

/// The first call of each apart, then calls in turn (`block` of each per round, so that every
/// one meets the machine's same moments) until `seconds` per call have passed (at least 11
/// rounds). With a block of one, each call finds the caches as the others left them. Each round
/// takes the calls in a new random order, so that each follows each other equally often: an
/// `openmp` call's team keeps spinning for a while after it returns (libgomp's wait policy),
/// which slowed whichever call came next (100 points on the 2-core VM: the default after
/// `openmp` in every round took 9.9 us, `serial` 7.1, for the same code).
std::vector<Calls> time_in_turn(const std::vector<std::function<void()>>& calls, double seconds, int block) {
  std::vector<Calls> timed(calls.size());
  horizon::Stopwatch clock;
  for (std::size_t k = 0; k < calls.size(); ++k) {
    clock.lap();
    calls[k]();
    timed[k].first_us = clock.lap() * 1e6;
  }
  const auto start = std::chrono::steady_clock::now();
  const auto spent = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const double budget = seconds * static_cast<double>(calls.size());
  std::vector<std::size_t> order(calls.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::mt19937 shuffler(1);
  for (std::size_t round = 0; round < 11 || (spent() < budget && round < 100000); ++round) {
    std::shuffle(order.begin(), order.end(), shuffler);
    for (const std::size_t k : order)
      for (int repeat = 0; repeat < block; ++repeat) {
        clock.lap();
        calls[k]();
        timed[k].us.push_back(clock.lap() * 1e6);
      }
  }
  for (Calls& c : timed) std::sort(c.us.begin(), c.us.end());
  return timed;
}

#if defined(HORIZON_WITH_VESIN)
/// vesin's full list of the points (open boundaries, ids only, rows unsorted) on one thread,
/// into `list`, reused from call to call as vesin intends; its length.
long long run_vesin(const horizon::PointSet& points, double cutoff, VesinNeighborList& list) {
  VesinOptions options{};
  options.cutoff = cutoff;
  options.full = true;
  options.sorted = false;
  options.algorithm = VesinAutoAlgorithm;
  options.n_threads = 1;
  const double box[3][3] = {};
  const bool periodic[3] = {false, false, false};
  const char* error = nullptr;
  if (vesin_neighbors(reinterpret_cast<const double(*)[3]>(points.xyz.data()), points.size(), box, periodic,
                      {VesinCPU, 0}, options, &list, &error) != 0) {
    std::fprintf(stderr, "vesin: %s\n", error ? error : "error");
    std::exit(1);
  }
  return static_cast<long long>(list.length);
}
#endif

double quantile(const std::vector<double>& sorted, double q) {
  return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(q * static_cast<double>(sorted.size())))];
}

}  // namespace

int run_latency(const LatencyOptions& options) {
  const int hardware = static_cast<int>(std::thread::hardware_concurrency());
  std::printf("# latency: random clouds with %g neighbours per point on average; %d hardware threads; %s; "
              "%d call(s) of each in turn\n",
              options.neighbours, hardware, horizon::cpu_simd_target(), std::max(1, options.block));
  std::printf("busy,points,backend,threads,calls,median_us,p99_us,max_us,first_us,entries\n");
  for (int busy : options.busy) {
    const int processes = busy < 0 ? hardware : busy;
    BusyProcesses load(processes);
    for (int n : options.sizes) {
      // Density for the wanted neighbours with horizon 1: n points in a cube of side L.
      const double side = std::cbrt(static_cast<double>(n) * 4.18879 / options.neighbours);
      const horizon::PointSet points = horizon::random_cloud(static_cast<std::size_t>(n), 3, 11, side);
      const auto report = [&](const char* name, int threads, const Calls& calls, long long entries) {
        std::printf("%d,%d,%s,%d,%zu,%.1f,%.1f,%.1f,%.1f,%lld\n", processes, n, name, threads, calls.us.size() + 1,
                    quantile(calls.us, 0.5), quantile(calls.us, 0.99), calls.us.back(), calls.first_us, entries);
        std::fflush(stdout);
      };
      // The textbook list, then each backend; the GPU's host path where a GPU is present.
      std::vector<horizon::Backend> backends{horizon::Backend::serial, horizon::Backend::openmp};
      if (horizon::backend_available(horizon::Backend::cuda)) backends.push_back(horizon::Backend::cuda);
      backends.push_back(horizon::Backend::automatic);
      std::vector<long long> entries(backends.size() + 1);
      std::vector<horizon::SearchStats> stats(backends.size());
      std::vector<std::function<void()>> calls{
          [&] { entries[0] = static_cast<long long>(textbook_cell_list(points, 1.0, 1).indices.size()); }};
#if defined(HORIZON_WITH_VESIN)
      VesinNeighborList vesin_list{};
      long long vesin_entries = 0;
      calls.push_back([&] { vesin_entries = run_vesin(points, 1.0, vesin_list); });
#endif
      const std::size_t first_backend = calls.size();
      for (std::size_t k = 0; k < backends.size(); ++k)
        calls.push_back([&, k] {
          horizon::SearchOptions search;
          search.horizon = 1.0;
          search.backend = backends[k];
          entries[k + 1] = horizon::search(points.view(), search, &stats[k]).total();
        });
      const std::vector<Calls> timed = time_in_turn(calls, options.seconds, std::max(1, options.block));
      report("textbook", 1, timed[0], entries[0]);
#if defined(HORIZON_WITH_VESIN)
      report("vesin", 1, timed[1], vesin_entries);
      vesin_free(&vesin_list);
#endif
      for (std::size_t k = 0; k < backends.size(); ++k) {
        const std::string name = backends[k] == horizon::Backend::automatic
                                     ? std::string("auto:") + horizon::backend_name(stats[k].backend)
                                     : horizon::backend_name(backends[k]);
        report(name.c_str(), stats[k].threads, timed[first_backend + k], entries[k + 1]);
      }
    }
  }
  return 0;
}

}  // namespace bench
