#pragma once
// The GPU anchor horizon must beat: the cell list as the CUDA samples and most papers write it.
// Bounds by CUB reductions, cell keys, CUB radix sort of (cell, id), cell start/end tables,
// coordinates gathered in cell order, then one thread per point walks the 27-cell stencil
// twice: a count pass, an exclusive scan, a fill pass. Rows unsorted, doubles, exact (same
// semantics as horizon: strict <, no self). Euclidean, 3-D, full list, cell side = horizon.
// It allocates from the device's default stream-ordered pool, kept warm between calls, so a
// repeated call pays no more for memory than horizon's pool.
#include <cstddef>
#include <cstdint>

namespace bench {

struct NaiveGpuResult {
  std::int64_t entries = 0;
  double seconds = 0;  ///< points on the GPU to the CSR on the GPU, one synchronisation
};

/// Builds the list of `count` points (AoS x y z in GPU memory) and frees it again.
NaiveGpuResult naive_gpu_cell_list(const double* xyz, std::size_t count, double horizon);

}  // namespace bench
