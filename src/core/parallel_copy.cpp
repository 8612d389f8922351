#include "parallel_copy.hpp"

#include <cstdint>
#include <cstring>

namespace horizon::detail {

void parallel_copy(void* to, const void* from, std::size_t bytes) {
  constexpr std::size_t piece = std::size_t{1} << 20;
  const auto pieces = static_cast<std::int64_t>((bytes + piece - 1) / piece);
#pragma omp parallel for schedule(static) if (pieces > 4)
  for (std::int64_t i = 0; i < pieces; ++i) {
    const std::size_t at = static_cast<std::size_t>(i) * piece;
    std::memcpy(static_cast<char*>(to) + at, static_cast<const char*>(from) + at,
                bytes - at < piece ? bytes - at : piece);
  }
}

}  // namespace horizon::detail
