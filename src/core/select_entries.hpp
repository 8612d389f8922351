#pragma once
// A sub-list: the entries of a list that pass a test, rows kept in order: a new list (the Verlet
// list's refresh, which keeps its candidates) or in the list's own arrays (the filters).
#include <algorithm>
#include <bit>
#include <cstring>
#include <vector>

#include <omp.h>

#include "parallel_scan.hpp"
#include "select_kernel.hpp"
#include "horizon/neighbor_list.hpp"

namespace horizon::detail {

/// The entries of each row that `mark(i, ids, count, bits)` marks: it sets bit e % 64 of
/// bits[e / 64] for each id ids[e] of row i it keeps (count of them) and returns how many.
/// The verdicts are kept as bits, each row's from a word of its own (about 1/32 of the list),
/// then the kept entries are written straight to their place: a temporary list moved
/// afterwards cost more, testing twice read each candidate's point twice, and a single pass
/// writing each thread's rows where they start, then moving them down, was no faster
/// (measured: Verlet refresh of lattice 100, m = 3.015).
template <class Mark>
NeighborList select_marked(const NeighborList& list, Mark mark, int threads) {
  const auto n = static_cast<std::int64_t>(list.size());
  const std::int64_t* from = list.offsets().data();
  // first_word[i]: where row i's bits start (a row of s entries takes ceil(s / 64) words).
  ScratchBuffer<std::int64_t> first_word(list.size() + 1);
  first_word[0] = 0;
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) first_word[i + 1] = (from[i + 1] - from[i] + 63) / 64;
  inclusive_scan(first_word.data(), first_word.size(), threads);
  ScratchBuffer<std::uint64_t> kept(static_cast<std::size_t>(first_word[n]));

  Buffer<std::int64_t> offsets(list.size() + 1);
  offsets[0] = 0;
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto row = list.row(static_cast<std::size_t>(i));
    offsets[i + 1] = mark(static_cast<std::size_t>(i), row.data(), static_cast<std::int64_t>(row.size()),
                          kept.data() + first_word[i]);
  }
  inclusive_scan(offsets.data(), offsets.size(), threads);
  Buffer<point_id> indices(static_cast<std::size_t>(offsets.back()));
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto row = list.row(static_cast<std::size_t>(i));
    point_id* out = indices.data() + offsets[i];
    const std::int64_t size = offsets[i + 1] - offsets[i];
    if (size == static_cast<std::int64_t>(row.size())) {  // all kept: no bits read
      if (!row.empty()) std::memcpy(out, row.data(), row.size() * sizeof(point_id));
    } else {
      write_marked(row.data(), static_cast<std::int64_t>(row.size()), kept.data() + first_word[i], size, out);
    }
  }
  return NeighborList(std::move(offsets), std::move(indices), list.is_half());
}

/// The entries j of each row i with keep(i, j), as select_marked() with a test per entry.
template <class Keep>
NeighborList select_entries(const NeighborList& list, Keep keep, int threads) {
  return select_marked(
      list,
      [&](std::size_t i, const point_id* ids, std::int64_t count, std::uint64_t* bits) {
        std::int64_t marked = 0;
        for (std::int64_t e = 0; e < count; e += 64) {
          const std::int64_t end = std::min(count, e + 64);
          std::uint64_t word = 0;
          for (std::int64_t f = e; f < end; ++f) word |= std::uint64_t{keep(i, ids[f])} << (f - e);
          bits[e / 64] = word;
          marked += std::popcount(word);
        }
        return marked;
      },
      threads);
}

/// Moves each row i < n of `data` down from from[i] to to[i] (to[i + 1] - to[i] entries),
/// where to[i] <= from[i] and from[i] - to[i] grows with i (rows only shrank), as memmoves row
/// by row in order would. Each entry is copied once: in waves of destinations, each split
/// among the threads; a thread first saves what it will read from where a later part of its
/// wave writes (less than the shift), the rows' gaps included.
inline void move_rows_down(point_id* data, const std::int64_t* from, const std::int64_t* to, std::int64_t n,
                           int threads) {
  // Rows that do not move come first.
  std::int64_t first = 0;
  for (std::int64_t step = n; step > 0; step /= 2)
    while (first + step <= n && from[first + step - 1] == to[first + step - 1]) first += step;
  constexpr std::int64_t wave = std::int64_t{1} << 20;
  for (std::int64_t begin = to[first]; begin < to[n]; begin += wave) {
    const std::int64_t end = std::min(to[n], begin + wave);
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
      const int parts = omp_get_num_threads(), part = omp_get_thread_num();
      const std::int64_t a = begin + (end - begin) * part / parts, b = begin + (end - begin) * (part + 1) / parts;
      // The row holding destination a, and where this part's reads start and end.
      const std::int64_t row = std::upper_bound(to + first, to + n + 1, a) - to - 1;
      auto source = [&](std::int64_t r, std::int64_t at) { return from[r] + (at - to[r]); };
      const std::int64_t last = b > a ? std::upper_bound(to + first, to + n + 1, b - 1) - to - 1 : row;
      const std::int64_t saved_from = std::max(b, source(row, a)), saved_to = std::min(end, source(last, b));
      std::vector<point_id> saved(static_cast<std::size_t>(std::max<std::int64_t>(0, saved_to - saved_from)));
      if (!saved.empty()) std::memcpy(saved.data(), data + saved_from, saved.size() * sizeof(point_id));
#pragma omp barrier
      // Copies `length` entries from source s to destination at: from data, from `saved`, then
      // from data again.
      auto copy = [&](std::int64_t at, std::int64_t s, std::int64_t length) {
        while (length > 0) {
          const bool in_saved = s >= saved_from && s < saved_to;
          const std::int64_t piece = std::min(length, in_saved ? saved_to - s : s < saved_from ? saved_from - s : length);
          std::memmove(data + at, in_saved ? saved.data() + (s - saved_from) : data + s,
                       static_cast<std::size_t>(piece) * sizeof(point_id));
          at += piece, s += piece, length -= piece;
        }
      };
      // Rows whose sources follow each other (after rows that did not shrink) in one copy: a
      // memmove per row took 1.26x (1 thread) and 2.0x (2 threads) the time (10^6 rows of 123
      // ids, 40 % of the second half shrunk; 2-core Zen 5 VM, bench/results/bond_filter_simd_2core_zen5).
      std::int64_t run_at = a, run_source = source(row, a), run_length = 0;
      for (std::int64_t r = row, at = a; at < b; ++r) {
        const std::int64_t piece = std::min(b, to[r + 1]) - at, s = source(r, at);
        if (piece == 0) continue;
        if (s != run_source + run_length) {
          copy(run_at, run_source, run_length);
          run_at = at, run_source = s, run_length = 0;
        }
        run_length += piece;
        at += piece;
      }
      copy(run_at, run_source, run_length);
    }
  }
}

/// The same in the list's own arrays, rows with `whole(i)` kept as they are, each other row i
/// compacted where it lies by `compact(i, row, count)`, which packs the entries it keeps to the
/// front of row[0, count) in order and returns how many: no second list, whose fresh pages cost
/// more than the tests (measured: ten cracks over lattice 100, m = 3.015, 2-core VM). The rows
/// are then moved down to their new offsets.
template <class Whole, class Compact>
NeighborList compact_rows(NeighborList&& list, Whole whole, Compact compact, int threads) {
  const bool half = list.is_half();
  auto [old_offsets, indices] = std::move(list).release();
  const auto n = static_cast<std::int64_t>(old_offsets.size()) - 1;
  Buffer<std::int64_t> offsets(old_offsets.size());
  offsets[0] = 0;
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t count = old_offsets[i + 1] - old_offsets[i];
    const auto row = static_cast<std::size_t>(i);
    offsets[i + 1] = whole(row) ? count : compact(row, indices.data() + old_offsets[i], count);
  }
  inclusive_scan(offsets.data(), offsets.size(), threads);
  if (offsets[n] == old_offsets[n]) return NeighborList(std::move(old_offsets), std::move(indices), half);

  move_rows_down(indices.data(), old_offsets.data(), offsets.data(), n, threads);
  indices.resize(static_cast<std::size_t>(offsets[n]));
  return NeighborList(std::move(offsets), std::move(indices), half);
}

/// compact_rows() with a test per entry: keep(i, j) for the entries j of each row i not whole.
template <class Whole, class Keep>
NeighborList select_entries(NeighborList&& list, Whole whole, Keep keep, int threads) {
  return compact_rows(
      std::move(list), whole,
      [&](std::size_t i, point_id* row, std::int64_t size) {
        std::int64_t count = 0;
        for (std::int64_t e = 0; e < size; ++e)
          if (keep(i, row[e])) row[count++] = row[e];
        return count;
      },
      threads);
}

}  // namespace horizon::detail
