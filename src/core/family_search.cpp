#include "family_search.hpp"

#include <hwy/contrib/sort/vqsort.h>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <bit>
#include <cstring>
#include <vector>

namespace horizon::detail {

namespace {

/// Sorts a family by id. Rows often arrive sorted or nearly so (input in lattice order), and
/// short rows sort fastest by insertion; longer shuffled rows go to highway's vectorised
/// quicksort, 6x faster than std::sort on 120 random ids (448 vs 2609 ns, this machine).
void sort_family(point_id* first, point_id* last) {
  if (last - first <= 32) {
    for (point_id* i = first + 1; i < last; ++i) {
      const point_id value = *i;
      point_id* j = i;
      for (; j > first && j[-1] > value; --j) *j = j[-1];
      *j = value;
    }
    return;
  }
  if (std::is_sorted(first, last)) return;
  static const hwy::Sorter sorter;
  sorter(first, static_cast<std::size_t>(last - first), hwy::SortAscending());
}

/// Appends order[t] for every t < length with hit[t] != 0 (hit is zero beyond length); returns
/// the new end. With AVX-512 a masked compress-store writes 16 at a time without a branch per
/// hit (measured on the CI machine, fill pass, random cloud of 10^6 points: 0.39 -> 0.27 s at
/// m = 1.5, 1.65 -> 1.20 s at m = 3.015); elsewhere the set bytes are walked eight at a time.
point_id* compress(const std::uint8_t* hit, int length, const point_id* order, point_id* out) {
#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__)
  for (int w = 0; w < length; w += 16) {
    const __mmask16 mask = _mm_test_epi8_mask(_mm_loadu_si128(reinterpret_cast<const __m128i*>(hit + w)),
                                              _mm_set1_epi8(1));
    const __m512i ids = _mm512_maskz_loadu_epi32(mask, order + w);  // masked lanes never fault
    _mm512_mask_compressstoreu_epi32(out, mask, ids);
    out += std::popcount(static_cast<unsigned>(mask));
  }
#else
  for (int w = 0; w < length; w += 8) {
    std::uint64_t bytes;
    std::memcpy(&bytes, hit + w, 8);
    for (; bytes; bytes &= bytes - 1) *out++ = order[w + (std::countr_zero(bytes) >> 3)];
  }
#endif
  return out;
}

/// The test of point p against candidate q: accumulated distance below the threshold, and q is
/// not p (half lists: q's id above p's).
template <Metric M, int D, bool Half>
struct PairTest {
  const double *x, *y, *z;
  const point_id* order;
  double threshold;

  bool operator()(std::int64_t p, point_id self, double xi, double yi, double zi,
                  std::int64_t q) const {
    const double d = metric_accumulate<M>(xi - x[q], yi - y[q], D == 3 ? zi - z[q] : 0.0);
    const bool keep = Half ? order[q] > self : q != p;
    return (d < threshold) & keep;
  }
};

/// Visits every point of the run with its stencil. Counting sums the pair test, a loop the
/// compiler vectorises. Filling evaluates the test for 64 candidates at a time into a byte
/// mask (vectorised too), then walks the set bytes eight at a time, writing each neighbour's
/// id straight into its row: no branch per candidate, no scratch copy.
template <Metric M, int D, bool Half, bool Fill>
void visit(const CellIndex& index, const SearchOptions& options, CellRun run,
           std::int64_t* offsets, point_id* indices) {
  const point_id* order = index.order().data();
  const PairTest<M, D, Half> test{index.coords(0).data(), index.coords(1).data(),
                                  index.coords(2).data(), order,
                                  metric_threshold(M, options.horizon)};
  std::vector<CellIndex::Range> rows(static_cast<std::size_t>(index.max_stencil_rows()));
  const std::size_t queries = options.queries ? options.queries : index.point_count();
  const auto points = static_cast<std::int64_t>(index.point_count());
  constexpr std::int64_t lookahead = 16;

  for (std::size_t c = run.first; c < run.last; ++c) {
    const int row_count = index.stencil(c, rows.data());
    const auto [first, last] = index.points_of(c);
    for (std::int64_t p = first; p < last; ++p) {
      const point_id self = order[p];
      // Rows are placed by input id: for input in random order every point's row (and its
      // offset) is a cache miss. Fetch them a few points ahead (measured: the fill pass on a
      // random cloud of 10^6 points, m = 1.5, went from 0.69 s to 0.39 s).
      if (p + 2 * lookahead < points) __builtin_prefetch(&offsets[order[p + 2 * lookahead]], 1);
      if constexpr (Fill)
        if (p + lookahead < points) __builtin_prefetch(indices + offsets[order[p + lookahead]], 1);
      if (static_cast<std::size_t>(self) >= queries) continue;  // offsets[self + 1] stays 0
      const double xi = test.x[p], yi = test.y[p], zi = test.z[p];
      if constexpr (!Fill) {
        std::int64_t found = 0;
        for (int r = 0; r < row_count; ++r)
          for (std::int64_t q = rows[r].begin; q < rows[r].end; ++q)
            found += test(p, self, xi, yi, zi, q);
        offsets[self + 1] = found;
      } else {
        point_id* out = indices + offsets[self];
        for (int r = 0; r < row_count; ++r) {
          for (std::int64_t block = rows[r].begin; block < rows[r].end; block += 64) {
            const int length = static_cast<int>(std::min<std::int64_t>(64, rows[r].end - block));
            alignas(64) std::uint8_t hit[64] = {};
            for (int t = 0; t < length; ++t) hit[t] = test(p, self, xi, yi, zi, block + t);
            out = compress(hit, length, order + block, out);
          }
        }
        if (options.sort_rows) sort_family(indices + offsets[self], out);
      }
    }
  }
}

template <bool Fill, Metric M, int D>
void visit_half(const CellIndex& index, const SearchOptions& options, CellRun run,
                std::int64_t* offsets, point_id* indices) {
  if (options.half)
    visit<M, D, true, Fill>(index, options, run, offsets, indices);
  else
    visit<M, D, false, Fill>(index, options, run, offsets, indices);
}

template <bool Fill, Metric M>
void visit_dims(const CellIndex& index, const SearchOptions& options, CellRun run,
                std::int64_t* offsets, point_id* indices) {
  if (index.grid().dims == 3)
    visit_half<Fill, M, 3>(index, options, run, offsets, indices);
  else
    visit_half<Fill, M, 2>(index, options, run, offsets, indices);
}

template <bool Fill>
void visit_metric(const CellIndex& index, const SearchOptions& options, CellRun run,
                  std::int64_t* offsets, point_id* indices) {
  switch (options.metric) {
    case Metric::euclidean: return visit_dims<Fill, Metric::euclidean>(index, options, run, offsets, indices);
    case Metric::manhattan: return visit_dims<Fill, Metric::manhattan>(index, options, run, offsets, indices);
    case Metric::chebyshev: return visit_dims<Fill, Metric::chebyshev>(index, options, run, offsets, indices);
  }
}

}  // namespace

void count_families(const CellIndex& index, const SearchOptions& options, CellRun run,
                    std::int64_t* offsets) {
  visit_metric<false>(index, options, run, offsets, nullptr);
}

void fill_families(const CellIndex& index, const SearchOptions& options, CellRun run,
                   const std::int64_t* offsets, point_id* indices) {
  // Filling only reads the offsets.
  visit_metric<true>(index, options, run, const_cast<std::int64_t*>(offsets), indices);
}

}  // namespace horizon::detail
