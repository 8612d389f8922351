// A short row of ids sorted in SIMD registers by a bitonic network: up to four vectors (64 ids
// with AVX-512, 32 with AVX2), padded with the largest id. An insertion sort of the 18-id rows
// of m = 1.5 mispredicts a branch per move when ids arrive in random order (AMD Zen 5: 350 ns
// a row; sorting took 60 % of the fill pass of a shuffled lattice); the network takes the same
// few dozen min/max/permute steps whatever the order (32 ns for 17-32 ids, 22 ns up to 16).
// Highway per-target header (included once per instruction set by foreach_target).
#if defined(HORIZON_SORT_NETWORK_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HORIZON_SORT_NETWORK_INL_H_
#undef HORIZON_SORT_NETWORK_INL_H_
#else
#define HORIZON_SORT_NETWORK_INL_H_
#endif

#include <hwy/highway.h>

#include <cstdint>
#include <limits>

HWY_BEFORE_NAMESPACE();
namespace horizon::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Sorts the N = vectors * Lanes(d) ids of `v` ascending (N a power of two) by a bitonic network
/// in the form without directions: each merge of two sorted blocks of k/2 compares element i
/// with its mirror in the block (i ^ (k - 1)), then halves (i ^ j, j = k/4 ... 1); the lower
/// index always takes the minimum. Element i = vector * lanes + lane: exchanges across vectors
/// are whole-vector min/max (the mirror reverses lanes), those within a vector permute lanes
/// with one constant index vector and mask per distance.
template <int vectors, class D, class V = hn::VFromD<D>>
HWY_INLINE void BitonicSort(D d, V* v) {
  constexpr int lanes = static_cast<int>(hn::MaxLanes(d));
  constexpr int n = vectors * lanes;
  const auto lane = hn::Iota(d, 0);
  // Within a vector: partner i ^ j and the upper lanes (bit j set) for j = 1, 2, 4, ...; the
  // mirror i ^ (k - 1) for k = 2, 4, ... (its upper lanes are those of j = k / 2).
  auto upper = [&](int j) { return hn::Ne(hn::And(lane, hn::Set(d, j)), hn::Zero(d)); };
  auto exchange = [&](V x, int partner_xor, int j) {
    const V partner = hn::TableLookupLanes(x, hn::IndicesFromVec(d, hn::Xor(lane, hn::Set(d, partner_xor))));
    return hn::IfThenElse(upper(j), hn::Max(x, partner), hn::Min(x, partner));
  };
#pragma GCC unroll 8
  for (int k = 2; k <= n; k *= 2) {
    if (k <= lanes) {
#pragma GCC unroll 8
      for (int a = 0; a < vectors; ++a) v[a] = exchange(v[a], k - 1, k / 2);
    } else {
      const int block = k / lanes;  // vectors per block of k
#pragma GCC unroll 8
      for (int a = 0; a < vectors; ++a) {
        const int first = a / block * block, mirror = first + block - 1 - (a - first);
        if (a >= mirror || mirror >= vectors) continue;  // (the bound for GCC's -Warray-bounds)
        const V reversed = hn::Reverse(d, v[mirror]);
        const V low = hn::Min(v[a], reversed), high = hn::Max(v[a], reversed);
        v[a] = low;
        v[mirror] = hn::Reverse(d, high);
      }
    }
#pragma GCC unroll 8
    for (int j = k / 4; j >= 1; j /= 2) {
      if (j >= lanes) {
        const int step = j / lanes;
#pragma GCC unroll 8
        for (int a = 0; a < vectors; ++a) {
          if ((a & step) || a + step >= vectors) continue;
          const V low = hn::Min(v[a], v[a + step]), high = hn::Max(v[a], v[a + step]);
          v[a] = low;
          v[a + step] = high;
        }
      } else {
#pragma GCC unroll 8
        for (int a = 0; a < vectors; ++a) v[a] = exchange(v[a], j, j);
      }
    }
  }
}

/// Sorts row[0, count) without the entry equal to `drop` (if any) and writes the first `kept`
/// of the result to out[0, kept): only those, the last vector by a masked store.
template <int vectors, class D, class T>
HWY_INLINE void SortVectors(D d, const T* row, std::int64_t count, T drop, T* out, std::int64_t kept) {
  using V = hn::VFromD<D>;
  constexpr auto lanes = static_cast<std::int64_t>(hn::MaxLanes(d));
  const V largest = hn::Set(d, std::numeric_limits<T>::max()), dropped = hn::Set(d, drop);
  V v[vectors];
#pragma GCC unroll 4
  for (int a = 0; a < vectors; ++a) {
    const std::int64_t left = count - a * lanes;
    if (left <= 0) {
      v[a] = largest;
      continue;
    }
    const V loaded = hn::LoadU(d, row + a * lanes);
    v[a] = hn::IfThenElse(hn::AndNot(hn::Eq(loaded, dropped), hn::FirstN(d, static_cast<std::size_t>(left))), loaded,
                          largest);
  }
  BitonicSort<vectors>(d, v);
#pragma GCC unroll 4
  for (int a = 0; a < vectors; ++a) {
    const std::int64_t left = kept - a * lanes;
    if (left >= lanes)
      hn::StoreU(v[a], d, out + a * lanes);
    else if (left > 0)
      hn::BlendedStore(v[a], hn::FirstN(d, static_cast<std::size_t>(left)), d, out + a * lanes);
  }
}

/// Writes row[0, count) ascending, without the one entry equal to `drop` when `kept` is count - 1,
/// to out[0, kept) when count <= 4 vectors of int32 and the vectors have at least 4 lanes;
/// returns false otherwise (nothing written). Reads up to a vector past `count`: the caller pads
/// the row by hn::Lanes(ScalableTag<T>). Writes nothing past out[kept - 1].
template <class T>
HWY_INLINE bool SortShortRowTo(const T* row, std::int64_t count, T drop, T* out, std::int64_t kept) {
  const hn::ScalableTag<T> d;
  constexpr auto lanes = static_cast<std::int64_t>(hn::MaxLanes(d));
  if constexpr (lanes < 4) {
    return false;
  } else {
    if (count > 4 * lanes) return false;
    if (count <= lanes)
      SortVectors<1>(d, row, count, drop, out, kept);
    else if (count <= 2 * lanes)
      SortVectors<2>(d, row, count, drop, out, kept);
    else
      SortVectors<4>(d, row, count, drop, out, kept);
    return true;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#endif
