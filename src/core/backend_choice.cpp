#include "backend_choice.hpp"

#include <fcntl.h>
#include <omp.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace horizon::detail {
namespace {

// Below this many points per thread a thread costs more than it saves (fork/join and barriers
// against its share of the work), and below serial_below points a team does: measured with
// horizon_bench --latency (docs/performance). 2-core Zen 3 VM: 1,000 points 225 us serial, 342
// on 2 threads; 2,000 points 444 against 288. 16-core Xeon: 10^4 points 2.6 ms serial, 0.54 ms
// on 16 threads (625 points each), 1.65 ms on the 2 the earlier 4,096 per thread gave.
constexpr std::size_t points_per_thread = 512;
constexpr std::size_t serial_below = 1536;
// The GPU's host path against the CPUs (horizon_bench --latency on the H100 machine).
constexpr std::size_t gpu_points_per_cpu = 1024;
constexpr std::size_t gpu_min_points = 4096;

/// The start of a small /proc file ("" when it cannot be read): one open and read, a few µs.
std::string read_proc(const char* path) {
  const int fd = open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {};
  char text[256] = {};
  const ssize_t length = read(fd, text, sizeof text - 1);
  close(fd);
  return length > 0 ? std::string(text, static_cast<std::size_t>(length)) : std::string();
}

/// A cgroup's CPU quota in CPUs, rounded up (0: none): cgroup v2's cpu.max, else v1's cfs files.
int cgroup_cpus() {
  double quota = 0, period = 0;
  char max[32] = {};
  if (std::sscanf(read_proc("/sys/fs/cgroup/cpu.max").c_str(), "%31s %lf", max, &period) == 2) {
    if (std::string(max) == "max" || period <= 0) return 0;
    quota = std::atof(max);
  } else if (std::sscanf(read_proc("/sys/fs/cgroup/cpu/cpu.cfs_quota_us").c_str(), "%lf", &quota) != 1 ||
             std::sscanf(read_proc("/sys/fs/cgroup/cpu/cpu.cfs_period_us").c_str(), "%lf", &period) != 1) {
    return 0;
  }
  if (quota <= 0 || period <= 0) return 0;
  return std::max(1, static_cast<int>(std::ceil(quota / period)));
}

}  // namespace

int usable_cpus() {
  static const int quota = cgroup_cpus();  // fixed for the process's life; the mask is not
  int cpus = omp_get_max_threads();
  cpu_set_t mask;
  if (sched_getaffinity(0, sizeof mask, &mask) == 0) cpus = std::min(cpus, CPU_COUNT(&mask));
  if (quota > 0) cpus = std::min(cpus, quota);
  return std::max(1, cpus);
}

int other_runnable_threads(int own) {
  // The fourth field of /proc/loadavg is "runnable/total" scheduling entities right now.
  double one, five, fifteen;
  int runnable = 0, total = 0;
  if (std::sscanf(read_proc("/proc/loadavg").c_str(), "%lf %lf %lf %d/%d", &one, &five, &fifteen, &runnable, &total) != 5)
    return 0;
  const int others = std::max(0, runnable - std::max(1, own));
  // A process starting beside us (a shell pipe's other end) is runnable for a moment too; only
  // contention that lasts counts: some task waited for a CPU in over a tenth of the last 10 s
  // (pressure stall information, where the kernel has it).
  double waiting = 0;
  const std::string pressure = read_proc("/proc/pressure/cpu");
  if (!pressure.empty() && std::sscanf(pressure.c_str(), "some avg10=%lf", &waiting) == 1 && waiting < 10.0) return 0;
  return others;
}

BackendChoice choose_backend(std::size_t points, const SearchOptions& options) {
  static thread_local int last_team = 1;  // this thread's last team: its workers may still be spinning
  BackendChoice choice;
  if (options.backend != Backend::automatic) {  // the CPUs are not asked for one core (a system call)
    choice.backend = options.backend;
    choice.threads = options.backend == Backend::serial ? 1 : options.threads > 0 ? options.threads : usable_cpus();
    choice.reason = "asked for";
    return choice;
  }
  if (options.threads <= 0 && options.devices.empty() && points < serial_below && points < gpu_min_points) {
    choice.backend = Backend::serial;  // no CPU or GPU count needed: a 10-point call takes ~0.4 us
    choice.threads = last_team = 1;
    choice.reason = "fewer than " + std::to_string(serial_below) + " points: one core";
    return choice;
  }
  const int cpus = usable_cpus();
  if (!options.devices.empty()) {
    choice.backend = Backend::cuda;
    choice.threads = cpus;
    choice.reason = "devices given";
    return choice;
  }
  if (options.threads > 0) {
    choice.threads = options.threads;
    choice.reason = "threads given";
  } else {
    const auto worth =
        points < serial_below ? 1 : static_cast<int>(std::min<std::size_t>(points / points_per_thread, 1 << 16));
    choice.threads = std::max(1, std::min(cpus, worth));
    choice.reason = choice.threads == cpus ? std::to_string(cpus) + " usable CPUs"
                                           : "points: " + std::to_string(points_per_thread) + " or more per thread";
    if (choice.threads > 1) {
      const int free = cpus - other_runnable_threads(last_team);
      if (free < choice.threads) {
        choice.threads = std::max(1, free);
        choice.reason = "cores busy: " + std::to_string(cpus - free) + " other runnable threads";
      }
    }
  }
  last_team = choice.threads;
  // The GPU's host path pays ~0.2-0.3 ms a call (launches, copies, synchronisation), which the
  // usable CPUs beat below about gpu_points_per_cpu points each (the H100 host's 16 cores:
  // equal at 10^4 points, the GPU 3.7x faster at 10^5). Its host copies use the chosen threads.
  const std::size_t crossover = std::max<std::size_t>(gpu_min_points, gpu_points_per_cpu * static_cast<std::size_t>(cpus));
  if (points >= crossover && backend_available(Backend::cuda)) {
    choice.backend = Backend::cuda;
    choice.reason = "a GPU is usable and wins above " + std::to_string(crossover) + " points here";
    return choice;
  }
  choice.backend = choice.threads > 1 ? Backend::openmp : Backend::serial;
  return choice;
}

}  // namespace horizon::detail
