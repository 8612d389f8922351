// The metric's accumulation of per-axis differences in SIMD lanes, with the arithmetic of
// metric_accumulate() (horizon/metric.hpp): no fused multiply-add, the same order of operations.
// Highway per-target header (included once per instruction set by foreach_target).
#if defined(HORIZON_METRIC_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HORIZON_METRIC_INL_H_
#undef HORIZON_METRIC_INL_H_
#else
#define HORIZON_METRIC_INL_H_
#endif

#include <hwy/highway.h>

#include "horizon/metric.hpp"

HWY_BEFORE_NAMESPACE();
namespace horizon::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <Metric M, int D, class V>
HWY_INLINE V accumulate(V dx, V dy, V dz) {
  if constexpr (M == Metric::euclidean) {
    const V xy = hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy));
    return D == 3 ? hn::Add(xy, hn::Mul(dz, dz)) : xy;
  } else if constexpr (M == Metric::manhattan) {
    const V xy = hn::Add(hn::Abs(dx), hn::Abs(dy));
    return D == 3 ? hn::Add(xy, hn::Abs(dz)) : xy;
  } else {
    const V xy = hn::Max(hn::Abs(dx), hn::Abs(dy));
    return D == 3 ? hn::Max(xy, hn::Abs(dz)) : xy;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace horizon::detail
HWY_AFTER_NAMESPACE();

#endif
