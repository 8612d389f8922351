// keep_bonds() (bond_kernel.hpp) for each instruction set: the masks of a vector of bonds'
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

  std::int64_t kept = 0;
  HWY_ALIGN point_id tail[HWY_MAX_BYTES / sizeof(std::uint64_t)];
  for (std::int64_t e = 0; e < count; e += lanes) {
    const std::int64_t valid = std::min(lanes, count - e);
    const point_id* from = ids + e;
    if (valid < lanes) {  // the last ids, padded with a valid one
      std::fill_n(tail, lanes, ids[e]);
      std::copy_n(ids + e, valid, tail);
      from = tail;
    }
    const auto id = hn::LoadU(di, from);
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
    unsigned keep = (bytes[0] | unsigned{bytes[1]} << 8) & ((1u << valid) - 1);
    if (!hn::AllFalse(d, undecided)) [[unlikely]] {
      HWY_ALIGN std::uint64_t filters[HWY_MAX_BYTES / sizeof(std::uint64_t)];
      hn::Store(open, d, filters);
      hn::StoreMaskBits(d, undecided, bytes);
      for (unsigned u = (bytes[0] | unsigned{bytes[1]} << 8) & ((1u << valid) - 1); u; u &= u - 1) {
        const int lane = std::countr_zero(u);
        if (decide(context, from[lane], static_cast<std::uint32_t>(filters[lane]))) keep |= 1u << lane;
      }
    }
    if (valid == lanes) {
      // Writes up to a vector from `kept` <= e: only over ids already loaded.
      StoreSelected(di, id, keep, ids + kept);
    } else {
      HWY_ALIGN point_id packed[HWY_MAX_BYTES / sizeof(std::uint64_t)];
      StoreSelected(di, id, keep, packed);
      std::copy_n(packed, std::popcount(keep), ids + kept);
    }
    kept += std::popcount(keep);
  }
  return kept;
}

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace horizon::detail {

HWY_EXPORT(KeepBonds);

std::int64_t keep_bonds(std::uint64_t own, const std::uint64_t* masks, point_id* ids, std::int64_t count,
                        DecideBond decide, const void* context) {
  return HWY_DYNAMIC_DISPATCH(KeepBonds)(own, masks, ids, count, decide, context);
}

}  // namespace horizon::detail
#endif
