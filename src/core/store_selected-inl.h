// Storing the id lanes a mask selects, packed to the front, with a register compress (or a table
// shuffle) and a plain store: AVX-512's compress-store to memory is microcoded on AMD Zen 4/5.
// Highway per-target header (included once per instruction set by foreach_target).
#include <cstdint>

#ifndef HORIZON_SHUFFLE_TABLE
#define HORIZON_SHUFFLE_TABLE
namespace horizon::detail {
/// Byte shuffles that move the 32-bit lanes selected by a mask of up to 4 bits to the front. A
/// static table: highway 1.0's own Compress for these vectors builds its table on the stack at
/// every call (GCC), and loading it back stalls on store forwarding (measured: AMD Zen 3, fill
/// pass of lattice 100, m = 3.015, 2.7 s with it).
struct alignas(16) LaneShuffles {
  std::uint8_t bytes[16][16];
};
constexpr LaneShuffles make_lane_shuffles() {
  LaneShuffles table{};
  for (int mask = 0; mask < 16; ++mask) {
    int out = 0;
    for (int lane = 0; lane < 4; ++lane)
      if (mask >> lane & 1) {
        for (int b = 0; b < 4; ++b) table.bytes[mask][4 * out + b] = static_cast<std::uint8_t>(4 * lane + b);
        ++out;
      }
    for (; out < 4; ++out)
      for (int b = 0; b < 4; ++b) table.bytes[mask][4 * out + b] = static_cast<std::uint8_t>(4 * out + b);
  }
  return table;
}
inline constexpr LaneShuffles lane_shuffles = make_lane_shuffles();
}  // namespace horizon::detail
#endif

#if defined(HORIZON_STORE_SELECTED_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HORIZON_STORE_SELECTED_INL_H_
#undef HORIZON_STORE_SELECTED_INL_H_
#else
#define HORIZON_STORE_SELECTED_INL_H_
#endif

#include <hwy/highway.h>

#include "horizon/neighbor_list.hpp"

HWY_BEFORE_NAMESPACE();
namespace horizon::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Writes the lanes of `ids` selected by `bits` to `out`, in lane order (and junk after them, up
/// to a vector). AVX-512 compresses in a register; narrower vectors shuffle by the table above.
template <class DI, class VI>
HWY_INLINE void StoreSelected(DI di, VI ids, unsigned bits, point_id* out) {
  if constexpr (hn::MaxLanes(di) == 1) {
    *out = hn::GetLane(ids);
  } else if constexpr (hn::MaxLanes(di) <= 4) {
    const hn::Repartition<std::uint8_t, DI> du8;
    const auto shuffle = hn::Load(du8, lane_shuffles.bytes[bits]);
    hn::StoreU(hn::BitCast(di, hn::TableLookupBytes(hn::BitCast(du8, ids), shuffle)), di, out);
  } else {
    const std::uint8_t bytes[8] = {static_cast<std::uint8_t>(bits), static_cast<std::uint8_t>(bits >> 8)};
    hn::StoreU(hn::Compress(ids, hn::LoadMaskBits(di, bytes)), di, out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#endif
