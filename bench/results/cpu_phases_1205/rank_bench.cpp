// Sorting short rows: the bitonic network (sort_network-inl.h) against ranks by broadcast
// compares and a scalar scatter. Rows: lattice 100, m = 1.5 (or 3.015), unsorted fill order.
#include <hwy/highway.h>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>
#include <algorithm>
#include "core/sort_network-inl.h"
#include "horizon/generate.hpp"
#include "horizon/search.hpp"
namespace hn = hwy::HWY_NAMESPACE;
using horizon::point_id;
using namespace horizon::detail::HWY_NAMESPACE;

template <int vectors>
HWY_INLINE void RankVectors(const point_id* row, std::int64_t count, point_id drop, point_id* out) {
  const hn::ScalableTag<point_id> d;
  using V = hn::VFromD<decltype(d)>;
  constexpr int lanes = hn::MaxLanes(d);
  HWY_ALIGN point_id tmp[vectors * lanes];
  HWY_ALIGN point_id rank[vectors * lanes];
  const V largest = hn::Set(d, std::numeric_limits<point_id>::max());
  V v[vectors], r[vectors];
  for (int a = 0; a < vectors; ++a) {
    const std::int64_t left = count - a * lanes;
    v[a] = left <= 0 ? largest : hn::IfThenElse(hn::FirstN(d, left), hn::LoadU(d, row + a * lanes), largest);
    hn::Store(v[a], d, tmp + a * lanes);
    r[a] = hn::Zero(d);
  }
#pragma GCC unroll 64
  for (int j = 0; j < vectors * lanes; ++j) {
    const V b = hn::Set(d, tmp[j]);
    for (int a = 0; a < vectors; ++a) r[a] = hn::Sub(r[a], hn::VecFromMask(d, hn::Lt(b, v[a])));
  }
  const V dropped = hn::Set(d, drop);
  for (int a = 0; a < vectors; ++a) hn::Store(hn::Add(r[a], hn::VecFromMask(d, hn::Gt(v[a], dropped))), d, rank + a * lanes);
  point_id sink;
  for (std::int64_t i = 0; i < count; ++i) {
    point_id* to = tmp[i] == drop ? &sink : out + rank[i];
    *to = tmp[i];
  }
}

bool RankRowTo(const point_id* row, std::int64_t count, point_id drop, point_id* out) {
  const hn::ScalableTag<point_id> d;
  constexpr int lanes = hn::MaxLanes(d);
  if (count <= lanes) RankVectors<1>(row, count, drop, out);
  else if (count <= 2 * lanes) RankVectors<2>(row, count, drop, out);
  else return false;
  return true;
}
HWY_NOINLINE bool NetRowTo(const point_id* row, std::int64_t count, point_id drop, point_id* out, std::int64_t kept) {
  return SortShortRowTo(row, count, drop, out, kept);
}
HWY_NOINLINE bool RankRowToNI(const point_id* row, std::int64_t count, point_id drop, point_id* out) {
  return RankRowTo(row, count, drop, out);
}

int main(int argc, char** argv) {
  const double m = argc > 1 ? atof(argv[1]) : 1.5;
  auto points = horizon::lattice(100);
  horizon::SearchOptions o; o.horizon = 0.1 * m; o.sort_rows = false; o.backend = horizon::Backend::serial;
  auto list = horizon::search(points.view(), o);
  const auto n = list.size();
  // rows with self put back at the end (as the fill's rows hold it), padded
  std::vector<std::int64_t> start(n + 1);
  std::vector<point_id> rows;
  for (std::size_t i = 0; i < n; ++i) {
    start[i] = rows.size();
    auto row = list.row(i);
    rows.insert(rows.end(), row.begin(), row.end());
    rows.insert(rows.begin() + start[i] + row.size() / 2, static_cast<point_id>(i));
  }
  start[n] = rows.size();
  rows.resize(rows.size() + 64, 0);
  std::vector<point_id> a(list.total() + 64), b(list.total() + 64);
  for (int rep = 0; rep < 5; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    std::int64_t at = 0, failed = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::int64_t c = start[i + 1] - start[i];
      failed += !NetRowTo(rows.data() + start[i], c, static_cast<point_id>(i), a.data() + at, c - 1);
      at += c - 1;
    }
    auto t1 = std::chrono::steady_clock::now();
    at = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::int64_t c = start[i + 1] - start[i];
      failed += !RankRowToNI(rows.data() + start[i], c, static_cast<point_id>(i), b.data() + at);
      at += c - 1;
    }
    auto t2 = std::chrono::steady_clock::now();
    std::printf("%s rows %zu failed %lld network %.1f ns/row, rank %.1f ns/row, equal %d\n", hwy::TargetName(HWY_TARGET), n,
                (long long)failed, std::chrono::duration<double>(t1 - t0).count() * 1e9 / n,
                std::chrono::duration<double>(t2 - t1).count() * 1e9 / n,
                std::memcmp(a.data(), b.data(), list.total() * sizeof(point_id)) == 0);
  }
}
