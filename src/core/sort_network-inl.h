// A short row of ids sorted in SIMD registers by a bitonic network: up to 64 ids (AVX2, AVX-512; 32
// with SSE4), padded with the largest id. An insertion sort of the 18-id rows
// of m = 1.5 mispredicts a branch per move when ids arrive in random order (AMD Zen 5: 350 ns
// a row; sorting took 60 % of the fill pass of a shuffled lattice); the network takes the same
// few dozen min/max/shuffle steps whatever the order, unrolled at compile time. With AVX2 every
// step is a constant shuffle within 128-bit blocks or a block swap and a blend with an
// immediate: with a general lane permute (vpermd) and variable blends, rows of 17-32 ids took
// 79 ns on AMD Zen 3, 35 ns now; up to 16 ids 28 ns, 15 ns now.
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

/// Lane i of `x` moved to lane i ^ Xor (Xor < lanes). Up to 8 lanes (SSE4, AVX2) by shuffles
/// within 128-bit blocks and a block swap: a general lane permute (vpermd) is two uops with a
/// long latency on AMD Zen 2/3. With AVX-512 by the one permute, which measured faster there
/// (Intel Xeon host: rows of 17-32 ids 31-34 ns, 38-41 with shuffles and block swaps).
template <int Xor, class D, class V>
HWY_INLINE V PartnerLanes(D d, V x) {
#if HWY_TARGET != HWY_SCALAR  // (which has none of these; its rows are not sorted here)
  if constexpr (hn::MaxLanes(d) <= 8) {
    if constexpr ((Xor & 4) != 0) x = hn::SwapAdjacentBlocks(x);
    if constexpr ((Xor & 3) == 1) return hn::Shuffle2301(x);
    if constexpr ((Xor & 3) == 2) return hn::Shuffle1032(x);
    if constexpr ((Xor & 3) == 3) return hn::Shuffle0123(x);
    return x;
  }
#endif
  return hn::TableLookupLanes(x, hn::IndicesFromVec(d, hn::Xor(hn::Iota(d, 0), hn::Set(d, Xor))));
}

/// The lanes with bit J set from `upper`, the others from `lower`: up to 8 lanes by blends with
/// an immediate, with AVX-512 by a mask (as measured fastest, see PartnerLanes).
template <int J, class D, class V>
HWY_INLINE V BlendUpperLanes(D d, V upper, V lower) {
#if HWY_TARGET != HWY_SCALAR
  if constexpr (hn::MaxLanes(d) <= 8) {
    if constexpr (J == 1) return hn::OddEven(upper, lower);
    if constexpr (J == 2) {
      const hn::Repartition<std::uint64_t, D> d64;
      return hn::BitCast(d, hn::OddEven(hn::BitCast(d64, upper), hn::BitCast(d64, lower)));
    }
    if constexpr (J == 4) return hn::OddEvenBlocks(upper, lower);
  }
#endif
  return hn::IfThenElse(hn::Ne(hn::And(hn::Iota(d, 0), hn::Set(d, J)), hn::Zero(d)), upper, lower);
}

/// Each lane paired with lane i ^ Xor: the one with bit J set keeps the larger.
template <int Xor, int J, class D, class V>
HWY_INLINE V Exchange(D d, V x) {
  const V partner = PartnerLanes<Xor>(d, x);
  return BlendUpperLanes<J>(d, hn::Max(x, partner), hn::Min(x, partner));
}

/// The halving steps of a bitonic merge: element i against i ^ J, J = J0, J0 / 2, ... 1.
template <int vectors, int J, class D, class V>
HWY_INLINE void HalveBlocks(D d, V* v) {
  if constexpr (J >= 1) {
    constexpr int lanes = static_cast<int>(hn::MaxLanes(d));
    if constexpr (J >= lanes) {
      constexpr int step = J / lanes;
#pragma GCC unroll 8
      for (int a = 0; a < vectors; ++a) {
        if ((a & step) || a + step >= vectors) continue;
        const V low = hn::Min(v[a], v[a + step]), high = hn::Max(v[a], v[a + step]);
        v[a] = low;
        v[a + step] = high;
      }
    } else {
#pragma GCC unroll 8
      for (int a = 0; a < vectors; ++a) v[a] = Exchange<J, J>(d, v[a]);
    }
    HalveBlocks<vectors, J / 2>(d, v);
  }
}

/// Sorts the N = vectors * Lanes(d) ids of `v` ascending (N a power of two) by a bitonic network
/// in the form without directions: each merge of two sorted blocks of K/2 compares element i
/// with its mirror in the block (i ^ (K - 1)), then halves (i ^ J, J = K/4 ... 1); the lower
/// index always takes the minimum. Element i = vector * lanes + lane: exchanges across vectors
/// are whole-vector min/max (the mirror reverses lanes), those within a vector shuffle lanes.
/// Unrolled at compile time, so that every shuffle and blend is a constant one.
template <int vectors, int K = 2, class D, class V = hn::VFromD<D>>
HWY_INLINE void BitonicSort(D d, V* v) {
  constexpr int lanes = static_cast<int>(hn::MaxLanes(d));
  if constexpr (K <= vectors * lanes) {
    if constexpr (K <= lanes) {
#pragma GCC unroll 8
      for (int a = 0; a < vectors; ++a) v[a] = Exchange<K - 1, K / 2>(d, v[a]);
    } else {
      constexpr int block = K / lanes;  // vectors per block of K
#pragma GCC unroll 8
      for (int a = 0; a < vectors; ++a) {
        const int first = a / block * block, mirror = first + block - 1 - (a - first);
        if (a >= mirror || mirror >= vectors) continue;  // (the bound for GCC's -Warray-bounds)
        const V reversed = PartnerLanes<lanes - 1>(d, v[mirror]);
        const V low = hn::Min(v[a], reversed), high = hn::Max(v[a], reversed);
        v[a] = low;
        v[mirror] = PartnerLanes<lanes - 1>(d, high);
      }
    }
    HalveBlocks<vectors, K / 4>(d, v);
    BitonicSort<vectors, 2 * K>(d, v);
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
/// to out[0, kept) when count <= ShortRowCapacity (8 vectors of at least 4 lanes);
/// returns false otherwise (nothing written). Reads up to a vector past `count`: the caller pads
/// the row by hn::Lanes(ScalableTag<T>). Writes nothing past out[kept - 1].
/// The longest row SortShortRowTo sorts, 8 vectors: 128 ids (AVX-512), 64 (AVX2), 32 (SSE4),
/// none below 4 lanes.
template <class T>
constexpr std::int64_t ShortRowCapacity() {
  constexpr auto lanes = static_cast<std::int64_t>(hn::MaxLanes(hn::ScalableTag<T>()));
  return lanes < 4 ? 0 : 8 * lanes;
}

template <class T>
HWY_INLINE bool SortShortRowTo(const T* row, std::int64_t count, T drop, T* out, std::int64_t kept) {
  const hn::ScalableTag<T> d;
  constexpr auto lanes = static_cast<std::int64_t>(hn::MaxLanes(d));
  if constexpr (lanes < 4) {
    return false;
  } else {
    constexpr std::int64_t most = ShortRowCapacity<T>() / lanes;  // vectors
    if (count > most * lanes) return false;
    if (count <= lanes)
      SortVectors<1>(d, row, count, drop, out, kept);
    else if (count <= 2 * lanes)
      SortVectors<2>(d, row, count, drop, out, kept);
    else if (count <= 4 * lanes)
      SortVectors<4>(d, row, count, drop, out, kept);
    else
      SortVectors<8>(d, row, count, drop, out, kept);
    return true;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#endif
