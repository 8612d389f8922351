#pragma once
// Copies into fresh host memory on all cores: one core cannot keep up with PCIe when the
// destination's pages are touched for the first time.
#include <cstddef>

#include "horizon/points.hpp"

namespace horizon::detail {

/// The threads the copies below use on the calling thread: omp_get_max_threads(), or while a
/// CopyThreads lives on this thread, its count (a search's own thread count: a copy that asks
/// for cores which other processes hold waits a scheduler time slice at its barrier).
int copy_threads();
class CopyThreads {
public:
  explicit CopyThreads(int threads);
  ~CopyThreads();
  CopyThreads(const CopyThreads&) = delete;
  CopyThreads& operator=(const CopyThreads&) = delete;

private:
  int saved_;
};

/// Copies with non-temporal stores where the CPU has them (the destination is not read back
/// first): on the H200 host a staged device -> host copy ran at 1.3x the PCIe floor this way
/// and at 1.9x with memcpy's ordinary stores. Each core takes whole 2 MB pieces of the
/// destination, so no two cores fault in one huge page, unless the copy is too small to give
/// every core one.
void parallel_copy(void* to, const void* from, std::size_t bytes);

/// parallel_copy's copy on the calling thread only.
void stream_copy(void* to, const void* from, std::size_t bytes);

/// Coordinates [first, first + count) of `points` (flattened, point after point) as doubles.
void parallel_copy_coordinates(double* to, PointView points, std::size_t first, std::size_t count);

/// Touches every page of [at, at + bytes) once, so that later copies into it do not fault.
void parallel_touch(void* at, std::size_t bytes);

/// Asks for transparent huge pages over the 2 MB-aligned interior of [at, at + bytes) (where
/// the kernel offers them on request): faulting in 16 GB took 0.30 s instead of 0.75 s on the
/// H200 host's 16 cores.
void advise_huge_pages(void* at, std::size_t bytes);

}  // namespace horizon::detail
