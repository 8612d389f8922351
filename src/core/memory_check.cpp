#include "memory_check.hpp"

#include <cstdio>
#include <fstream>
#include <string>

#include "horizon/buffer.hpp"
#include "horizon/error.hpp"

namespace horizon::detail {
namespace {

/// MemAvailable from /proc/meminfo, in bytes (0 when it cannot be read).
std::size_t memory_available() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::size_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

std::string size_text(std::size_t bytes) {
  char text[32];
  const double b = static_cast<double>(bytes);
  if (b >= 1e9) std::snprintf(text, sizeof(text), "%.2f GB", b / 1e9);
  else if (b >= 1e6) std::snprintf(text, sizeof(text), "%.1f MB", b / 1e6);
  else std::snprintf(text, sizeof(text), "%zu bytes", bytes);
  return text;
}

}  // namespace

void check_list_fits(std::int64_t entries, const SearchOptions& options, std::size_t bytes_per_entry) {
  const std::size_t needed = static_cast<std::size_t>(entries) * bytes_per_entry;
  // Reading /proc/meminfo costs ~20 us, a seventh of a 1,000-point search: small lists are
  // not worth asking about (without a limit of the caller's).
  constexpr std::size_t worth_asking = std::size_t{64} << 20;
  if (options.max_memory == 0 && needed < worth_asking) return;
  // The blocks kept for the next lists are free memory to this search (allocate_large reuses
  // or frees them).
  const std::size_t available = memory_available();
  const std::size_t limit = options.max_memory ? options.max_memory
                            : available      ? available + cached_buffer_bytes()
                                             : 0;
  if (limit == 0 || needed <= limit) return;
  std::string what = "the neighbour list needs " + size_text(needed) + " (" + std::to_string(entries) +
                     " entries) but " + size_text(limit) +
                     (options.max_memory ? " are allowed (max memory)" : " of memory are available") + "; ";
  what += options.half ? "a smaller horizon, or the distributed search over more nodes (mpirun), would fit"
                       : "a half list (--half) needs half of it; or a smaller horizon, or more nodes (mpirun)";
  throw ListTooLarge(what, needed, limit);
}

}  // namespace horizon::detail
