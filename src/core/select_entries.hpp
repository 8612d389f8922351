#pragma once
// A sub-list: the entries of a list that pass a test, rows kept in order: a new list (the Verlet
// list's refresh, which keeps its candidates) or in the list's own arrays (the filters).
#include <algorithm>
#include <bit>
#include <cstring>

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

/// Moves data[from, from + size) down to data[to, ...) (to <= from). In parallel, in waves no
/// longer than the shift, so no part of a wave writes where another still reads; a small shift
/// (many short waves) moves in one memmove.
inline void move_down(point_id* data, std::int64_t to, std::int64_t from, std::int64_t size, int threads) {
  const std::int64_t shift = from - to;
  if (shift == 0 || size <= 0) return;
  constexpr std::int64_t shortest_wave = std::int64_t{1} << 16;
  if (threads <= 1 || shift < shortest_wave) {
    std::memmove(data + to, data + from, static_cast<std::size_t>(size) * sizeof(point_id));
    return;
  }
  for (std::int64_t done = 0; done < size; done += shift) {
    const std::int64_t wave = std::min(shift, size - done);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int part = 0; part < threads; ++part) {
      const std::int64_t first = wave * part / threads, last = wave * (part + 1) / threads;
      if (last > first)
        std::memcpy(data + to + done + first, data + from + done + first, static_cast<std::size_t>(last - first) * sizeof(point_id));
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

  // Rows move down (offsets[i] <= old_offsets[i]): each chunk of rows in parallel to where its
  // first row lies, then the chunks in order to their places.
  const std::int64_t chunks = std::max(1, threads);
  auto chunk_first = [&](std::int64_t t) { return n * t / chunks; };
#pragma omp parallel for schedule(static, 1) num_threads(threads) if (threads > 1)
  for (std::int64_t t = 0; t < chunks; ++t) {
    std::int64_t to = old_offsets[chunk_first(t)];
    for (std::int64_t i = chunk_first(t); i < chunk_first(t + 1); ++i) {
      const std::int64_t size = offsets[i + 1] - offsets[i];
      if (to != old_offsets[i] && size > 0)
        std::memmove(indices.data() + to, indices.data() + old_offsets[i], static_cast<std::size_t>(size) * sizeof(point_id));
      to += size;
    }
  }
  for (std::int64_t t = 0; t < chunks; ++t) {
    const std::int64_t from = old_offsets[chunk_first(t)], to = offsets[chunk_first(t)];
    move_down(indices.data(), to, from, offsets[chunk_first(t + 1)] - to, threads);
  }
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
