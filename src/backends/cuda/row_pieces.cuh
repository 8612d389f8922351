#pragma once
// Included by search.cu only (one translation unit): definitions in an anonymous namespace.
// Where the rows of a range of ids lie in sorted (cell) order. The list is laid out by id and
// the fill kernels run in sorted order, so a fill of some rows only (a batch, or a piece of the
// list to be copied out while the next is filled) visits just the sorted positions those ids
// hold. The count pass notes them for row_pieces equal pieces of the ids; a range of ids then
// takes the positions of the pieces it meets. Points given in spatial order (a mesh, a
// lattice) keep a piece within a few slabs of cells; points in random order spread every piece
// over all positions, and the fills still skip the other rows one by one.
#include <climits>
#include <cstdint>
#include <utility>

#include "device_index.cuh"

namespace horizon::detail {
namespace {

constexpr int row_pieces = 64;

/// lo[b], hi[b]: the first and one past the last sorted position of the rows of ids
/// [b * ids_per_piece, (b + 1) * ids_per_piece), lowered and raised from UINT_MAX and 0.
/// Positions of a warp ascend with the lane, so the lowest and highest lane of a piece hold its
/// warp's bounds.
__global__ void piece_positions(DeviceIndexView ix, std::int64_t ids_per_piece, unsigned* lo, unsigned* hi) {
  __shared__ unsigned block_lo[row_pieces], block_hi[row_pieces];
  for (int b = threadIdx.x; b < row_pieces; b += blockDim.x) {
    block_lo[b] = UINT_MAX;
    block_hi[b] = 0;
  }
  __syncthreads();
  const std::int64_t p = blockIdx.x * static_cast<std::int64_t>(blockDim.x) + threadIdx.x;
  const point_id self = p < ix.n ? ix.order[p] : ix.queries;
  const int piece = ix.has_row(self) ? static_cast<int>(self / ids_per_piece) : -1;  // -1: holds no row
  const unsigned same = __match_any_sync(0xffffffffu, piece);
  const int lane = threadIdx.x % 32;
  if (piece >= 0 && lane == __ffs(same) - 1) atomicMin(&block_lo[piece], static_cast<unsigned>(p));
  if (piece >= 0 && lane == 31 - __clz(same)) atomicMax(&block_hi[piece], static_cast<unsigned>(p + 1));
  __syncthreads();
  for (int b = threadIdx.x; b < row_pieces; b += blockDim.x)
    if (block_hi[b]) {
      atomicMin(lo + b, block_lo[b]);
      atomicMax(hi + b, block_hi[b]);
    }
}

/// The sorted positions of each piece of the rows, as the count pass found them (host copy).
struct RowPieces {
  std::int64_t ids_per_piece = 1;
  unsigned lo[row_pieces], hi[row_pieces];

  /// Sorted positions [first, second) that hold every row of ids [first, last).
  std::pair<std::int64_t, std::int64_t> positions(std::int64_t first, std::int64_t last) const {
    std::int64_t begin = INT64_MAX, end = 0;
    for (std::int64_t b = first / ids_per_piece; b < row_pieces && b * ids_per_piece < last; ++b)
      if (hi[b] > 0) {
        begin = std::min<std::int64_t>(begin, lo[b]);
        end = std::max<std::int64_t>(end, hi[b]);
      }
    return end > 0 ? std::pair{begin, end} : std::pair<std::int64_t, std::int64_t>{0, 0};
  }
};

/// Starts piece_positions over the index on `stream`; `device` holds 2 * row_pieces unsigned
/// (lo, then hi), `host` is filled once the stream has passed this point.
void find_row_pieces(const DeviceIndexView& ix, std::int64_t rows, unsigned* device, RowPieces& host,
                     cudaStream_t stream) {
  host.ids_per_piece = std::max<std::int64_t>(1, (rows + row_pieces - 1) / row_pieces);
  HORIZON_CUDA_CHECK(cudaMemsetAsync(device, 0xff, row_pieces * sizeof(unsigned), stream));
  HORIZON_CUDA_CHECK(cudaMemsetAsync(device + row_pieces, 0, row_pieces * sizeof(unsigned), stream));
  if (ix.n > 0) {
    piece_positions<<<blocks_for(static_cast<std::size_t>(ix.n)), block_size, 0, stream>>>(
        ix, host.ids_per_piece, device, device + row_pieces);
    check_launch("piece_positions");
  }
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(host.lo, device, row_pieces * sizeof(unsigned), cudaMemcpyDeviceToHost, stream));
  HORIZON_CUDA_CHECK(cudaMemcpyAsync(host.hi, device + row_pieces, row_pieces * sizeof(unsigned),
                                     cudaMemcpyDeviceToHost, stream));
}

}  // namespace
}  // namespace horizon::detail
