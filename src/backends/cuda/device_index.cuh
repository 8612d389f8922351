#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// Binning (thesis §5.2's binning kernel): the grid from a CUB reduction of the bounds, points
// sorted by cell with CUB radix sort, a cell start table (dense grids) or sorted cell
// coordinates (sparse grids), and the coordinates gathered in sorted order.
#include <cub/cub.cuh>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>

#include <limits>

#include "device_memory.hpp"
#include "horizon/grid.hpp"
#include "horizon/search.hpp"
#include "device_list_access.hpp"
#include "launch.cuh"

namespace horizon::detail {
namespace {

struct Box {
  double lo[3], hi[3];
};

struct PointBox {
  const double* xyz;
  int dims;
  // Axes spelled out: a loop to the run-time `dims` kept the box in local memory (and
  // cell_keys' cell coordinates likewise: 266 us for 8e6 points on an H200, 4x the naive
  // anchor's binning kernel).
  __host__ __device__ Box operator()(std::int64_t i) const {
    const double* p = xyz + i * dims;
    const double z = dims == 3 ? p[2] : 0.0;
    return Box{{p[0], p[1], z}, {p[0], p[1], z}};
  }
};

struct MergeBoxes {
  __host__ __device__ Box operator()(const Box& a, const Box& b) const {
    Box m;
    for (int d = 0; d < 3; ++d) {
      m.lo[d] = fmin(a.lo[d], b.lo[d]);
      m.hi[d] = fmax(a.hi[d], b.hi[d]);
    }
    return m;
  }
};

/// The grid's parameters, by value in every kernel.
struct GridParams {
  double origin[3];
  double side;
  std::int64_t cells[3];
  int k, dims;
  bool dense;

  __device__ std::int64_t cell_of(double x, int axis) const {
    return static_cast<std::int64_t>(floor((x - origin[axis]) / side)) + k;
  }
  __device__ std::int64_t linear(std::int64_t cx, std::int64_t cy, std::int64_t cz) const {
    return cx + cells[0] * (cy + cells[1] * cz);
  }
};

GridParams params_of(const Grid& g) {
  GridParams p{};
  for (int a = 0; a < 3; ++a) {
    p.origin[a] = g.origin[a];
    p.cells[a] = g.cells[a];
  }
  p.side = g.cell_side;
  p.k = g.cells_per_horizon;
  p.dims = g.dims;
  p.dense = g.dense;
  return p;
}

__global__ void cell_keys(const double* xyz, std::int64_t n, GridParams g, std::int64_t* linear,
                          std::int64_t* kx, std::int64_t* ky, std::int64_t* kz, point_id* ids) {
  const std::int64_t i = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (i >= n) return;
  const double* p = xyz + i * g.dims;
  const std::int64_t cx = g.cell_of(p[0], 0), cy = g.cell_of(p[1], 1), cz = g.dims == 3 ? g.cell_of(p[2], 2) : 0;
  if (g.dense) {
    linear[i] = g.linear(cx, cy, cz);
  } else {
    kx[i] = cx;
    ky[i] = cy;
    kz[i] = cz;
  }
  ids[i] = static_cast<point_id>(i);
}

template <typename T>
__global__ void gather(const T* from, const point_id* order, std::int64_t n, T* to) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p < n) to[p] = from[order[p]];
}

__global__ void gather_coords(const double* xyz, int dims, const point_id* order, std::int64_t n,
                              double* x, double* y, double* z) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= n) return;
  const std::int64_t i = order[p];
  x[p] = xyz[i * dims];
  y[p] = xyz[i * dims + 1];
  z[p] = dims == 3 ? xyz[i * dims + 2] : 0.0;
}

template <typename T>
__device__ std::int64_t lower_bound(const T* sorted, std::int64_t n, T value) {
  std::int64_t lo = 0, hi = n;
  while (lo < hi) {
    const std::int64_t mid = (lo + hi) / 2;
    if (sorted[mid] < value) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

// flags[p] = whether sorted position p is the first of its cell (dense: linear ids in a;
// sparse: cell coordinates in a, b, c).
__global__ void mark_cell_firsts(const std::int64_t* a, const std::int64_t* b, const std::int64_t* c,
                                 std::int64_t n, unsigned char* flags) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p >= n) return;
  flags[p] = p == 0 || a[p] != a[p - 1] || (b && (b[p] != b[p - 1] || c[p] != c[p - 1]));
}

// id[p] = order[p], or for a periodic image (order[p] >= rows) the id of the point it copies.
__global__ void name_images(const point_id* order, std::int64_t n, std::int64_t rows, const point_id* image_of,
                            point_id* id) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p < n) id[p] = order[p] < rows ? order[p] : image_of[order[p] - rows];
}

// id[p] = names[order[p]]: a GPU part's points by their global ids.
__global__ void name_points(const point_id* order, std::int64_t n, const point_id* names, point_id* id) {
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (p < n) id[p] = names[order[p]];
}

// start[c] = first sorted position of a cell with linear id >= c.
__global__ void cell_starts(const std::int64_t* sorted_keys, std::int64_t n, std::int64_t cells,
                            std::int64_t* start) {
  const std::int64_t c = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  if (c <= cells) start[c] = lower_bound(sorted_keys, n, c);
}

/// Points sorted by cell on the GPU: everything the build kernels read, by value.
struct DeviceIndexView {
  GridParams grid;
  std::int64_t n, queries;  // points 0 .. queries-1 get families
  const double *x, *y, *z;
  const point_id* order;  // the point at each sorted position (its row)
  const point_id* id;     // the id families name it by: order, but periodic images as their
                          // originals and a GPU part's points by their global ids
  const std::int64_t* start;              // dense: linear id -> first sorted position
  const std::int64_t *kx, *ky, *kz;       // sparse: sorted cell coordinates per point
  const std::int64_t* cell_first;         // first sorted position of each occupied cell
  const std::int64_t* cell_count;         // number of occupied cells (one value)
  const std::uint8_t* row_mask;           // when given, only points with row_mask[id] != 0 get families

  __device__ bool has_row(point_id self) const { return self < queries && (!row_mask || row_mask[self]); }

  // Sorted positions of the cells (cx-k .. cx+k, cy, cz).
  __device__ void row(std::int64_t cx, std::int64_t cy, std::int64_t cz, std::int64_t& begin,
                      std::int64_t& end) const {
    const int k = grid.k;
    if (grid.dense) {
      begin = start[grid.linear(cx - k, cy, cz)];
      end = start[grid.linear(cx + k, cy, cz) + 1];
      return;
    }
    begin = sparse_bound(cz, cy, cx - k);
    end = sparse_bound(cz, cy, cx + k + 1);
  }
  // First sorted position whose (kz, ky, kx) is not below (cz, cy, cx).
  __device__ std::int64_t sparse_bound(std::int64_t cz, std::int64_t cy, std::int64_t cx) const {
    std::int64_t lo = 0, hi = n;
    while (lo < hi) {
      const std::int64_t mid = (lo + hi) / 2;
      const bool below = kz[mid] < cz || (kz[mid] == cz && (ky[mid] < cy || (ky[mid] == cy && kx[mid] < cx)));
      if (below) lo = mid + 1;
      else hi = mid;
    }
    return lo;
  }
};

/// What a pass writes: counts[id] = |family| and the widest stencil (count pass), or the rows
/// of the ids in [first, last) at out[offsets[id] - base] (fill passes).
struct PassArgs {
  double threshold;
  int sort_bits;  // ids are below 2^sort_bits - 1
  std::int64_t* counts;
  unsigned long long* widest;
  unsigned long long* long_rows;  // count pass: rows longer than the short-row fill stages
  point_id* spilled;              // short-row fill: ids of the rows it stored unstaged...
  unsigned* spill_count;          // ...and their number
  const std::int64_t* offsets;
  point_id* out;
  point_id first, last;                   // fills: the rows of ids [first, last)...
  std::int64_t position_first, position_last;  // ...which lie at these sorted positions
  std::int64_t base;
  unsigned* bits;                     // hit bits (hit_bits.cuh): written by the count pass...
  const std::int64_t* bit_offsets;    // ...at bits + bit_offsets[p], p the sorted position
};

class DeviceIndex {
public:
  /// The last `images` of the `count` points may be periodic images, which hold no row; image k
  /// is found as point image_of[k] (device memory). A GPU part's points are named by `naming`
  /// (device memory), and only its own points get rows.
  DeviceIndex(const double* xyz, std::size_t count, int dims, const SearchOptions& options,
              cudaStream_t stream, MemoryMeter& meter, std::size_t images = 0, const point_id* image_of = nullptr,
              const PartNaming* naming = nullptr)
      : n_(static_cast<std::int64_t>(count)), rows_(static_cast<std::int64_t>(count - images)),
        name_bound_(naming ? naming->bound : n_), row_mask_(naming ? naming->own : nullptr), x_(count, meter),
        y_(count, meter), z_(count, meter), order_(count, meter), id_(images || naming ? count : 0, meter), start_(0, meter),
        kx_(0, meter), ky_(0, meter), kz_(0, meter), cell_first_(count, meter), cell_count_(1, meter) {
    grid_ = Grid::from_bounds(reduce_bounds(xyz, count, dims, stream, meter), dims, count, options.horizon,
                              options.cells_per_horizon);
    const GridParams g = params_of(grid_);
    DeviceArray<point_id> ids(count, meter), ids_sorted(count, meter);
    DeviceArray<unsigned char> firsts(count, meter);
    if (g.dense) {
      DeviceArray<std::int64_t> keys(count, meter), sorted(count, meter);
      cell_keys<<<blocks_for(count), block_size, 0, stream>>>(xyz, n_, g, keys.get(), nullptr, nullptr, nullptr, ids.get());
      check_launch("cell_keys");
      const auto cells = static_cast<std::int64_t>(grid_.cell_count());
      int bits = 1;
      while ((std::int64_t{1} << bits) <= cells) ++bits;
      sort_pairs(keys.get(), sorted.get(), ids.get(), order_.get(), bits, stream, meter);
      start_ = DeviceArray<std::int64_t>(static_cast<std::size_t>(cells) + 1, meter);
      cell_starts<<<blocks_for(static_cast<std::size_t>(cells) + 1), block_size, 0, stream>>>(
          sorted.get(), n_, cells, start_.get());
      check_launch("cell_starts");
      mark_cell_firsts<<<blocks_for(count), block_size, 0, stream>>>(sorted.get(), nullptr, nullptr, n_, firsts.get());
    } else {
      sort_sparse(xyz, g, ids, ids_sorted, stream, meter);
      mark_cell_firsts<<<blocks_for(count), block_size, 0, stream>>>(kx_.get(), ky_.get(), kz_.get(), n_, firsts.get());
    }
    check_launch("mark_cell_firsts");
    list_cells(firsts.get(), stream, meter);
    gather_coords<<<blocks_for(count), block_size, 0, stream>>>(xyz, dims, order_.get(), n_, x_.get(), y_.get(), z_.get());
    check_launch("gather_coords");
    if (images) {
      name_images<<<blocks_for(count), block_size, 0, stream>>>(order_.get(), n_, rows_, image_of, id_.get());
      check_launch("name_images");
    }
    if (naming) {
      name_points<<<blocks_for(count), block_size, 0, stream>>>(order_.get(), n_, naming->names, id_.get());
      check_launch("name_points");
    }
  }

  DeviceIndexView view(std::size_t queries) const {
    return {params_of(grid_), n_, queries ? static_cast<std::int64_t>(queries) : rows_, x_.get(), y_.get(), z_.get(),
            order_.get(), id_.size() ? id_.get() : order_.get(), start_.get(), kx_.get(), ky_.get(), kz_.get(),
            cell_first_.get(), cell_count_.get(), row_mask_};
  }
  std::int64_t size() const { return n_; }
  /// One past the largest id a family may hold.
  std::int64_t name_bound() const { return name_bound_; }
  /// The points that hold rows: all but the images.
  std::int64_t rows() const { return rows_; }

private:
  static Bounds reduce_bounds(const double* xyz, std::size_t count, int dims, cudaStream_t stream,
                              MemoryMeter& meter);
  void sort_pairs(const std::int64_t* keys, std::int64_t* sorted, const point_id* ids,
                  point_id* ids_sorted, int bits, cudaStream_t stream, MemoryMeter& meter) const;
  void sort_sparse(const double* xyz, const GridParams& g, DeviceArray<point_id>& ids,
                   DeviceArray<point_id>& ids_sorted, cudaStream_t stream, MemoryMeter& meter);
  void list_cells(const unsigned char* firsts, cudaStream_t stream, MemoryMeter& meter);

  std::int64_t n_, rows_, name_bound_;
  const std::uint8_t* row_mask_;
  Grid grid_;
  DeviceArray<double> x_, y_, z_;
  DeviceArray<point_id> order_, id_;
  DeviceArray<std::int64_t> start_, kx_, ky_, kz_;
  DeviceArray<std::int64_t> cell_first_, cell_count_;
};

// The occupied cells, by their first sorted position; their number stays on the device (the
// per-cell kernels read it), so listing them costs no synchronisation.
void DeviceIndex::list_cells(const unsigned char* firsts, cudaStream_t stream, MemoryMeter& meter) {
  const thrust::counting_iterator<std::int64_t> positions(0);
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceSelect::Flagged(nullptr, temp_bytes, positions, firsts, cell_first_.get(),
                                                cell_count_.get(), n_, stream));
  DeviceArray<char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceSelect::Flagged(temp.get(), temp_bytes, positions, firsts, cell_first_.get(),
                                                cell_count_.get(), n_, stream));
}

Bounds DeviceIndex::reduce_bounds(const double* xyz, std::size_t count, int dims,
                                  cudaStream_t stream, MemoryMeter& meter) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const Box init{{inf, inf, inf}, {-inf, -inf, -inf}};
  const auto boxes = thrust::make_transform_iterator(thrust::counting_iterator<std::int64_t>(0), PointBox{xyz, dims});
  DeviceArray<Box> result(1, meter);
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceReduce::Reduce(nullptr, temp_bytes, boxes, result.get(),
                                               static_cast<std::int64_t>(count), MergeBoxes(), init, stream));
  DeviceArray<char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceReduce::Reduce(temp.get(), temp_bytes, boxes, result.get(),
                                               static_cast<std::int64_t>(count), MergeBoxes(), init, stream));
  Box box;
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(&box, result.get(), sizeof(Box), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaStreamSynchronize(stream));
  Bounds bounds;
  for (int a = 0; a < 3; ++a) {
    bounds.lo[a] = box.lo[a];
    bounds.hi[a] = box.hi[a];
  }
  return bounds;
}

void DeviceIndex::sort_pairs(const std::int64_t* keys, std::int64_t* sorted, const point_id* ids,
                             point_id* ids_sorted, int bits, cudaStream_t stream,
                             MemoryMeter& meter) const {
  std::size_t temp_bytes = 0;
  HORIZON_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, temp_bytes, keys, sorted, ids, ids_sorted,
                                                     n_, 0, bits, stream));
  DeviceArray<char> temp(temp_bytes, meter);
  HORIZON_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp.get(), temp_bytes, keys, sorted, ids, ids_sorted,
                                                     n_, 0, bits, stream));
}

// Sparse grids: three stable radix sorts, by x, then y, then z cell coordinate, give the
// lexicographic (z, y, x) order without ever forming a linear id that could overflow.
void DeviceIndex::sort_sparse(const double* xyz, const GridParams& g, DeviceArray<point_id>& ids,
                              DeviceArray<point_id>& ids_sorted, cudaStream_t stream,
                              MemoryMeter& meter) {
  const auto count = static_cast<std::size_t>(n_);
  DeviceArray<std::int64_t> kx(count, meter), ky(count, meter), kz(count, meter);
  DeviceArray<std::int64_t> gathered(count, meter), sorted(count, meter);
  cell_keys<<<blocks_for(count), block_size, 0, stream>>>(xyz, n_, g, nullptr, kx.get(), ky.get(), kz.get(), ids.get());
  check_launch("cell_keys");
  const std::int64_t* by_axis[3] = {kx.get(), ky.get(), kz.get()};
  for (int a = 0; a < 3; ++a) {
    gather<<<blocks_for(count), block_size, 0, stream>>>(by_axis[a], ids.get(), n_, gathered.get());
    check_launch("gather");
    int bits = 1;
    while ((std::int64_t{1} << bits) <= g.cells[a]) ++bits;
    sort_pairs(gathered.get(), sorted.get(), ids.get(), ids_sorted.get(), bits, stream, meter);
    std::swap(ids, ids_sorted);
  }
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(order_.get(), ids.get(), count * sizeof(point_id), cudaMemcpyDeviceToDevice, stream));
  kx_ = DeviceArray<std::int64_t>(count, meter);
  ky_ = DeviceArray<std::int64_t>(count, meter);
  kz_ = DeviceArray<std::int64_t>(count, meter);
  DeviceArray<std::int64_t>* sorted_axes[3] = {&kx_, &ky_, &kz_};
  for (int a = 0; a < 3; ++a) {
    gather<<<blocks_for(count), block_size, 0, stream>>>(by_axis[a], order_.get(), n_, sorted_axes[a]->get());
    check_launch("gather");
  }
}

}  // namespace
}  // namespace horizon::detail
