#pragma once
// What Backend::automatic runs, and on how many threads: the problem's size, the CPUs this
// process may use (affinity mask, cgroup quota, the caller's OpenMP limit) and how many other
// threads are running right now. A search that shares its cores with busy processes waits at
// every barrier for a descheduled thread (a scheduler time slice each, up to 1,000x one core's
// time on a 2-core VM), so it takes only the cores that are free.
#include <cstddef>
#include <string>

#include "horizon/search.hpp"

namespace horizon::detail {

struct BackendChoice {
  Backend backend = Backend::serial;
  int threads = 1;
  std::string reason;  ///< why, for SearchStats::choice and the CLI's --json
};

/// The backend and thread count of a search of `points` points with `options`; an explicit
/// backend is kept (its threads bounded by the usable CPUs unless options.threads is set).
BackendChoice choose_backend(std::size_t points, const SearchOptions& options);

/// CPUs this process may run threads on: the affinity mask, a cgroup CPU quota and
/// omp_get_max_threads() (the caller's OMP_NUM_THREADS or omp_set_num_threads), whichever is least.
int usable_cpus();

/// Runnable threads on the machine now besides the calling one (/proc/loadavg), less `own`
/// threads of this process that may still be spinning from the last parallel region.
int other_runnable_threads(int own);

}  // namespace horizon::detail
