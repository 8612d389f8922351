#pragma once
// memcpy on all cores: one core cannot keep up with PCIe when the destination's pages are
// touched for the first time.
#include <cstddef>

namespace horizon::detail {

void parallel_copy(void* to, const void* from, std::size_t bytes);

}  // namespace horizon::detail
