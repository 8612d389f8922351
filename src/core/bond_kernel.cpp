// plane_sides() and keep_bonds() (bond_kernel.hpp) for each instruction set. A point's sides of
// all planes are one or two vectors of planes. The masks of a vector of bonds'
// other ends are gathered by id, every field tested in lanes, and the kept ids packed to the
// front of the row with a register compress or a table shuffle (store_selected-inl.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/bond_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cstring>

#include "core/bond_kernel.hpp"
#include "core/store_selected-inl.h"

HWY_BEFORE_NAMESPACE();
namespace horizon::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void PlaneSides(PointView points, std::size_t begin, std::size_t end, const Planes& planes, double reach,
                std::uint64_t* masks) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  const auto zero = hn::Zero(d), limit = hn::Set(d, reach);
  const bool flat = points.dims() == 2;
  for (std::size_t i = begin; i < end; ++i) {
    const auto x = hn::Set(d, points(i, 0)), y = hn::Set(d, points(i, 1)), z = hn::Set(d, flat ? 0.0 : points(i, 2));
    std::uint64_t above = 0, below = 0, close = 0;
    for (std::size_t f = 0; f < static_cast<std::size_t>(planes.count); f += lanes) {
      auto along = [&](const decltype(x)& at, int a) {
        return hn::Mul(hn::Sub(at, hn::LoadU(d, planes.origin[a] + f)), hn::LoadU(d, planes.normal[a] + f));
      };
      const auto side = hn::Add(hn::Add(along(x, 0), along(y, 1)), along(z, 2));
      std::uint8_t bits[8] = {};
      auto field = [&](const auto& mask) {
        hn::StoreMaskBits(d, mask, bits);
        return (std::uint64_t{bits[0]} | std::uint64_t{bits[1]} << 8) << f;
      };
      above |= field(hn::Gt(side, zero));
      below |= field(hn::Lt(side, zero));
      close |= field(hn::Lt(hn::Abs(side), limit));
    }
    const std::uint64_t used = (std::uint64_t{1} << planes.count) - 1;
    masks[i] = (above & used) << BondMasks::above | (below & used) << BondMasks::below |
               (close & used) << BondMasks::near;
  }
}

std::int64_t KeepBonds(std::uint64_t own, const std::uint64_t* masks, point_id* ids, std::int64_t count,
                       DecideBond decide, const void* context) {
  const hn::ScalableTag<std::uint64_t> d;
  const hn::Rebind<std::int64_t, decltype(d)> d64;
  const hn::Rebind<point_id, decltype(d)> di;
  const auto lanes = static_cast<std::int64_t>(hn::Lanes(d));
  constexpr std::uint64_t field = 0xFFFF;
  // The row's point's fields, and what of them every bond uses.
  const std::uint64_t a_above = own >> BondMasks::above & field, a_below = own >> BondMasks::below & field;
  const std::uint64_t a_near = own >> BondMasks::near & field, a_deep = own >> BondMasks::deep & field;
  const std::uint64_t a_on = a_near & ~(a_above | a_below);
  const auto above = hn::Set(d, a_above), below = hn::Set(d, a_below), near = hn::Set(d, a_near);
  const auto deep = hn::Set(d, a_deep), off = hn::Set(d, a_above | a_below), on = hn::Set(d, a_on);
  const auto on_deep = hn::Set(d, a_on & a_deep), low = hn::Set(d, field), zero = hn::Zero(d);

  // The bits of the lanes of `id` to keep, of those in `valid`.
  auto keep_bits = [&](const hn::Vec<decltype(di)> id, unsigned valid) {
    const auto w = hn::GatherIndex(d, masks, hn::BitCast(d64, hn::PromoteTo(d64, id)));
    const auto b_above = hn::And(w, low), b_below = hn::And(hn::ShiftRight<BondMasks::below>(w), low);
    const auto b_near = hn::And(hn::ShiftRight<BondMasks::near>(w), low);
    const auto b_deep = hn::ShiftRight<BondMasks::deep>(w);
    const auto b_off = hn::Or(b_above, b_below), b_on = hn::AndNot(b_off, b_near);
    const auto across = hn::Or(hn::And(above, b_below), hn::And(below, b_above));
    const auto cut = hn::Or(hn::Or(hn::And(hn::And(across, deep), b_deep), hn::And(on_deep, b_off)),
                            hn::And(hn::And(b_on, b_deep), off));
    const auto apart = hn::Or(hn::Or(hn::And(above, b_above), hn::And(below, b_below)), hn::And(on, b_on));
    const auto open = hn::AndNot(apart, hn::And(near, b_near));
    const auto is_cut = hn::Ne(cut, zero);
    const auto undecided = hn::AndNot(is_cut, hn::Ne(open, zero));
    std::uint8_t bytes[8] = {};
    hn::StoreMaskBits(d, hn::Not(hn::Or(is_cut, undecided)), bytes);
    unsigned keep = bytes[0] & valid;
    if (!hn::AllFalse(d, undecided)) [[unlikely]] {
      HWY_ALIGN std::uint64_t filters[HWY_MAX_BYTES / sizeof(std::uint64_t)];
      HWY_ALIGN point_id lane_id[HWY_MAX_BYTES / sizeof(std::uint64_t)];
      hn::Store(open, d, filters);
      hn::Store(id, di, lane_id);
      hn::StoreMaskBits(d, undecided, bytes);
      for (unsigned u = bytes[0] & valid; u; u &= u - 1) {
        const int lane = std::countr_zero(u);
        if (decide(context, lane_id[lane], static_cast<std::uint32_t>(filters[lane]))) keep |= 1u << lane;
      }
    }
    return keep;
  };

  const unsigned all = (1u << lanes) - 1;
  std::int64_t kept = 0, e = 0;
  for (; e + lanes <= count; e += lanes) {
    const auto id = hn::LoadU(di, ids + e);
    const unsigned keep = keep_bits(id, all);
    StoreSelected(di, id, keep, ids + kept);  // up to a vector from kept <= e: over ids already loaded
    kept += std::popcount(keep);
  }
  if (e < count) {  // the last ids, copied: a masked load or store is a whole one on some targets
    HWY_ALIGN point_id last[HWY_MAX_BYTES / sizeof(std::uint64_t)] = {};  // id 0 past the row
    std::copy_n(ids + e, count - e, last);
    const auto id = hn::Load(di, last);
    const unsigned keep = keep_bits(id, (1u << (count - e)) - 1);
    StoreSelected(di, id, keep, last);
    std::copy_n(last, std::popcount(keep), ids + kept);
    kept += std::popcount(keep);
  }
  return kept;
}

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace horizon::detail {

HWY_EXPORT(PlaneSides);
HWY_EXPORT(KeepBonds);

void plane_sides(PointView points, std::size_t begin, std::size_t end, const Planes& planes, double reach,
                 std::uint64_t* masks) {
  HWY_DYNAMIC_DISPATCH(PlaneSides)(points, begin, end, planes, reach, masks);
}

std::int64_t keep_bonds(std::uint64_t own, const std::uint64_t* masks, point_id* ids, std::int64_t count,
                        DecideBond decide, const void* context) {
  return HWY_DYNAMIC_DISPATCH(KeepBonds)(own, masks, ids, count, decide, context);
}

}  // namespace horizon::detail
#endif
