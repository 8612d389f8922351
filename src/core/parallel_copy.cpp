#include "parallel_copy.hpp"

#include <cstdint>
#include <cstring>

namespace horizon::detail {

namespace {
constexpr std::size_t piece = std::size_t{1} << 20;
}

void parallel_copy(void* to, const void* from, std::size_t bytes) {
  const auto pieces = static_cast<std::int64_t>((bytes + piece - 1) / piece);
#pragma omp parallel for schedule(static) if (pieces > 4)
  for (std::int64_t i = 0; i < pieces; ++i) {
    const std::size_t at = static_cast<std::size_t>(i) * piece;
    std::memcpy(static_cast<char*>(to) + at, static_cast<const char*>(from) + at,
                bytes - at < piece ? bytes - at : piece);
  }
}

void parallel_copy_coordinates(double* to, PointView points, std::size_t first, std::size_t count) {
  if (!points.is_float32()) {
    parallel_copy(to, points.float64_data() + first, count * sizeof(double));
    return;
  }
  const auto dims = static_cast<std::size_t>(points.dims());
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (n > (1 << 16))
  for (std::int64_t i = 0; i < n; ++i) {
    const std::size_t at = first + static_cast<std::size_t>(i);
    to[i] = points(at / dims, static_cast<int>(at % dims));
  }
}

void parallel_touch(void* at, std::size_t bytes) {
  constexpr std::size_t page = 4096;
  const auto pages = static_cast<std::int64_t>((bytes + page - 1) / page);
  char* base = static_cast<char*>(at);
#pragma omp parallel for schedule(static) if (pages > 256)
  for (std::int64_t i = 0; i < pages; ++i) base[static_cast<std::size_t>(i) * page] = 0;
}

}  // namespace horizon::detail
