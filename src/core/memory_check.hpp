#pragma once
// The list's size is known after the count pass: refuse it, with its size and the ways out,
// before allocating what the machine does not have (instead of being killed by the kernel).
#include <cstdint>

#include "horizon/search.hpp"

namespace horizon::detail {

/// Throws ListTooLarge when `entries` ids would exceed options.max_memory or, when that is 0,
/// the memory the system reports available (Linux MemAvailable; no check where unknown).
void check_list_fits(std::int64_t entries, const SearchOptions& options, std::size_t bytes_per_entry = sizeof(point_id));

}  // namespace horizon::detail
