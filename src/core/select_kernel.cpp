// mark_within() and write_marked() (select_kernel.hpp) for each instruction set. A candidate's
// coordinates lie wherever its id puts them, so the test loads them per candidate; it puts four
// candidates' (x, y) pairs into two 256-bit registers and unpacks them into x and y lanes (and z
// from two halves): half the instructions of the scalar test, which was issue-bound (the test
// of a Verlet refresh of lattice 100, m = 3.015, one AMD Zen 3 core: 0.18-0.20 s scalar, 0.10 s
// so; with AVX2 gathers 0.26 s).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/select_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>

#include "core/metric-inl.h"
#include "core/select_kernel.hpp"
#include "core/store_selected-inl.h"

HWY_BEFORE_NAMESPACE();
namespace horizon::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_ARCH_X86 && HWY_TARGET != HWY_EMU128 && HWY_TARGET != HWY_SCALAR
// Candidates per step: four in 256-bit vectors where the target has them, else two.
using Pair = hn::Full128<double>;
using Lanes = hn::CappedTag<double, HWY_MAX_BYTES >= 32 ? 4 : 2>;

/// Lanes of candidates ids[0, 4) (or [0, 2)) as vectors of their x, y and z.
template <int D>
HWY_INLINE void LoadCandidates(const point_id* ids, const double* xyz, hn::Vec<Lanes>& x, hn::Vec<Lanes>& y,
                               hn::Vec<Lanes>& z) {
  const Lanes d;
  const hn::Full64<double> one;
  auto at = [&](int lane) { return xyz + D * static_cast<std::size_t>(ids[lane]); };
  if constexpr (hn::MaxLanes(d) == 4) {
    const auto ac = hn::Combine(d, hn::LoadU(Pair(), at(2)), hn::LoadU(Pair(), at(0)));  // xa ya xc yc
    const auto bd = hn::Combine(d, hn::LoadU(Pair(), at(3)), hn::LoadU(Pair(), at(1)));  // xb yb xd yd
    x = hn::InterleaveLower(d, ac, bd);
    y = hn::InterleaveUpper(d, ac, bd);
    if constexpr (D == 3)
      z = hn::Combine(d, hn::Combine(Pair(), hn::LoadU(one, at(3) + 2), hn::LoadU(one, at(2) + 2)),
                      hn::Combine(Pair(), hn::LoadU(one, at(1) + 2), hn::LoadU(one, at(0) + 2)));
  } else {
    const auto a = hn::LoadU(d, at(0)), b = hn::LoadU(d, at(1));
    x = hn::InterleaveLower(d, a, b);
    y = hn::InterleaveUpper(d, a, b);
    if constexpr (D == 3) z = hn::Combine(d, hn::LoadU(one, at(1) + 2), hn::LoadU(one, at(0) + 2));
  }
}
#endif

/// The bits of candidates [begin, end) (at most 64) of a row, bit 0 for `begin`.
template <Metric M, int D>
HWY_INLINE std::uint64_t MarkWord(const double* point, const point_id* ids, std::int64_t begin, std::int64_t end,
                                  const double* xyz, double threshold) {
  std::uint64_t word = 0;
  std::int64_t e = begin;
#if HWY_ARCH_X86 && HWY_TARGET != HWY_EMU128 && HWY_TARGET != HWY_SCALAR
  const Lanes d;
  const auto lanes = static_cast<std::int64_t>(hn::MaxLanes(d));
  const auto px = hn::Set(d, point[0]), py = hn::Set(d, point[1]), pz = hn::Set(d, D == 3 ? point[2] : 0.0);
  const auto limit = hn::Set(d, threshold);
  for (; e + lanes <= end; e += lanes) {
    hn::Vec<Lanes> x, y, z;
    LoadCandidates<D>(ids + e, xyz, x, y, z);
    const auto dx = hn::Sub(px, x), dy = hn::Sub(py, y);
    const auto dz = D == 3 ? hn::Sub(pz, z) : dx;
    std::uint8_t near[8];
    hn::StoreMaskBits(d, hn::Lt(accumulate<M, D>(dx, dy, dz), limit), near);
    word |= std::uint64_t{near[0]} << (e - begin);
  }
#endif
  for (; e < end; ++e) {
    const double* q = xyz + D * static_cast<std::size_t>(ids[e]);
    const double dz = D == 3 ? point[2] - q[2] : 0.0;
    word |= std::uint64_t{metric_accumulate<M>(point[0] - q[0], point[1] - q[1], dz) < threshold} << (e - begin);
  }
  return word;
}

template <Metric M, int D>
std::int64_t MarkRow(const double* point, const point_id* ids, std::int64_t count, const double* xyz,
                     double threshold, std::uint64_t* bits) {
  std::int64_t marked = 0;
  for (std::int64_t e = 0; e < count; e += 64) {
    const std::uint64_t word = MarkWord<M, D>(point, ids, e, std::min(count, e + 64), xyz, threshold);
    bits[e / 64] = word;
    marked += std::popcount(word);
  }
  return marked;
}

std::int64_t MarkWithin(Metric metric, int dims, const double* point, const point_id* ids, std::int64_t count,
                        const double* xyz, double threshold, std::uint64_t* bits) {
  switch (metric) {
    case Metric::manhattan:
      return dims == 3 ? MarkRow<Metric::manhattan, 3>(point, ids, count, xyz, threshold, bits)
                       : MarkRow<Metric::manhattan, 2>(point, ids, count, xyz, threshold, bits);
    case Metric::chebyshev:
      return dims == 3 ? MarkRow<Metric::chebyshev, 3>(point, ids, count, xyz, threshold, bits)
                       : MarkRow<Metric::chebyshev, 2>(point, ids, count, xyz, threshold, bits);
    default:
      return dims == 3 ? MarkRow<Metric::euclidean, 3>(point, ids, count, xyz, threshold, bits)
                       : MarkRow<Metric::euclidean, 2>(point, ids, count, xyz, threshold, bits);
  }
}

void WriteMarked(const point_id* ids, std::int64_t count, const std::uint64_t* bits, std::int64_t marked,
                 point_id* out) {
  const hn::Rebind<point_id, hn::ScalableTag<double>> di;
  const auto lanes = static_cast<std::int64_t>(hn::Lanes(di));  // divides 64
  std::int64_t e = 0, written = 0;
  // A vector store writes junk past the marked ids: only while it stays within this row.
  for (; e + lanes <= count && written + lanes <= marked; e += lanes) {
    const auto selected = static_cast<unsigned>(bits[e / 64] >> (e % 64)) & ((1u << lanes) - 1);
    StoreSelected(di, hn::LoadU(di, ids + e), selected, out + written);
    written += std::popcount(selected);
  }
  // Branch-free: every id is written and the place advances past the marked ones; the loop
  // stops at the last marked one.
  for (; written < marked; ++e) {
    out[written] = ids[e];
    written += static_cast<std::int64_t>(bits[e / 64] >> (e % 64) & 1);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace horizon::detail {

HWY_EXPORT(MarkWithin);
HWY_EXPORT(WriteMarked);

std::int64_t mark_within(Metric metric, int dims, const double* point, const point_id* ids, std::int64_t count,
                         const double* xyz, double threshold, std::uint64_t* bits) {
  return HWY_DYNAMIC_DISPATCH(MarkWithin)(metric, dims, point, ids, count, xyz, threshold, bits);
}

void write_marked(const point_id* ids, std::int64_t count, const std::uint64_t* bits, std::int64_t marked,
                  point_id* out) {
  HWY_DYNAMIC_DISPATCH(WriteMarked)(ids, count, bits, marked, out);
}

}  // namespace horizon::detail
#endif
