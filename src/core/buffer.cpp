#include "horizon/buffer.hpp"

namespace horizon::detail {

// No madvise(MADV_HUGEPAGE): with the kernel's default THP defrag policy the first huge-page
// faults compact memory synchronously (measured on the CI machine: 1.0 s instead of 0.16 s to
// fault in 470 MB).
void* allocate_large(std::size_t bytes) {
  if (void* p = std::malloc(bytes ? bytes : 1)) return p;
  throw std::bad_alloc();
}

void release_large(void* pointer) noexcept { std::free(pointer); }

}  // namespace horizon::detail
