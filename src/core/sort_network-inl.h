// A short row of ids sorted in SIMD registers by a bitonic network: up to four vectors (64 ids
// with AVX-512, 32 with AVX2), padded with the largest id. An insertion sort of the 18-id rows
// of m = 1.5 mispredicts a branch per move when ids arrive in random order (measured on AMD
// Zen 5: sorting took 60 % of the fill pass of a shuffled lattice); the network takes the same
// few dozen min/max/permute steps whatever the order. Highway per-target header (included once
// per instruction set by foreach_target).
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

/// One compare-exchange step of a bitonic network between lanes i and i ^ j of `v`: the lane
/// whose bit j is set takes the larger value where `ascending`, the smaller elsewhere.
template <class D, class V, class M>
HWY_INLINE V ExchangeLanes(D d, V v, int j, M ascending) {
  const auto lane = hn::Iota(d, 0);
  const V partner = hn::TableLookupLanes(v, hn::IndicesFromVec(d, hn::Xor(lane, hn::Set(d, j))));
  const auto upper = hn::Ne(hn::And(lane, hn::Set(d, j)), hn::Zero(d));
  const auto take_max = hn::Not(hn::Xor(upper, ascending));  // upper == ascending
  return hn::IfThenElse(take_max, hn::Max(v, partner), hn::Min(v, partner));
}

/// Sorts the N = vectors * Lanes(d) ids of `v` ascending (N a power of two): the classic
/// bitonic network, element i = vector * lanes + lane. Exchanges across vectors are whole-vector
/// min/max; those within a vector permute lanes.
template <int vectors, class D, class V = hn::VFromD<D>>
HWY_INLINE void BitonicSort(D d, V* v) {
  constexpr int lanes = static_cast<int>(hn::MaxLanes(d));
  const auto lane = hn::Iota(d, 0);
  constexpr int n = vectors * lanes;
#pragma GCC unroll 8
  for (int k = 2; k <= n; k *= 2) {
#pragma GCC unroll 8
    for (int j = k / 2; j >= 1; j /= 2) {
      if (j >= lanes) {
        const int step = j / lanes;
#pragma GCC unroll 4
        for (int a = 0; a < vectors; ++a) {
          if ((a & step) || a + step >= vectors) continue;
          const bool ascending = ((a * lanes) & k) == 0;
          const V low = hn::Min(v[a], v[a + step]), high = hn::Max(v[a], v[a + step]);
          v[a] = ascending ? low : high;
          v[a + step] = ascending ? high : low;
        }
      } else {
#pragma GCC unroll 4
        for (int a = 0; a < vectors; ++a) {
          // Direction: bit k of the element index, in the lane (k < lanes) or the vector.
          const auto ascending = k < lanes ? hn::Eq(hn::And(lane, hn::Set(d, k)), hn::Zero(d))
                                           : (((a * lanes) & k) == 0 ? hn::FirstN(d, lanes) : hn::FirstN(d, 0));
          v[a] = ExchangeLanes(d, v[a], j, ascending);
        }
      }
    }
  }
}

template <int vectors, class D, class T>
HWY_INLINE void SortVectors(D d, T* row, std::int64_t count) {
  using V = hn::VFromD<D>;
  constexpr auto lanes = static_cast<std::int64_t>(hn::MaxLanes(d));
  const V largest = hn::Set(d, std::numeric_limits<T>::max());
  V v[vectors];
#pragma GCC unroll 4
  for (int a = 0; a < vectors; ++a) {
    const std::int64_t left = count - a * lanes;
    v[a] = left <= 0 ? largest
                     : hn::IfThenElse(hn::FirstN(d, static_cast<std::size_t>(left)), hn::LoadU(d, row + a * lanes),
                                      largest);
  }
  BitonicSort<vectors>(d, v);
  for (int a = 0; a < vectors && a * lanes < count; ++a) hn::StoreU(v[a], d, row + a * lanes);
}

/// Number of i in [0, count - 1) with row[i] > row[i + 1]; reads up to a vector past `count`.
template <class T>
HWY_INLINE std::int64_t CountDescents(const T* row, std::int64_t count) {
  const hn::ScalableTag<T> d;
  constexpr auto lanes = static_cast<std::int64_t>(hn::MaxLanes(d));
  std::int64_t descents = 0;
  for (std::int64_t i = 0; i + 1 < count; i += lanes) {
    const auto pairs = hn::FirstN(d, static_cast<std::size_t>(count - 1 - i));
    descents += static_cast<std::int64_t>(
        hn::CountTrue(d, hn::And(pairs, hn::Gt(hn::LoadU(d, row + i), hn::LoadU(d, row + i + 1)))));
  }
  return descents;
}

/// Sorts row[0, count) ascending when count <= 4 vectors of int32 and the vectors have at least
/// 4 lanes; returns false otherwise (the row untouched). Reads and writes up to a vector past
/// `count`: the caller pads the row by hn::Lanes(ScalableTag<T>).
template <class T>
HWY_INLINE bool SortShortRow(T* row, std::int64_t count) {
  const hn::ScalableTag<T> d;
  constexpr auto lanes = static_cast<std::int64_t>(hn::MaxLanes(d));
  if constexpr (lanes < 4) {
    return false;
  } else {
    if (count > 4 * lanes) return false;
    if (count <= 1) return true;
    if (count <= lanes)
      SortVectors<1>(d, row, count);
    else if (count <= 2 * lanes)
      SortVectors<2>(d, row, count);
    else
      SortVectors<4>(d, row, count);
    return true;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#endif
