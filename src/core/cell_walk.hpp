#pragma once
// One row of a cell search's list from the candidates the engine found among the wrapped
// points and their images: each candidate mapped to its point and shift, measured again on the
// caller's coordinates, kept or dropped as the oracle does, and given in (j, S) order. The CPU's
// and the GPU's cell searches both walk their rows with it, so both take the same decisions.
#include <cstddef>
#include <cstdint>

#include "cell_problem.hpp"

namespace horizon::detail {

/// What maps a candidate k of the engine's list to its point and shift (the arrays of Images,
/// in host or GPU memory): k < points is wrapped point k, the others image k - points.
struct ImageTables {
  const double* original = nullptr;         ///< the caller's coordinates, dims per point
  const std::int32_t* wraps = nullptr;      ///< per point: x = wrapped + w . cell (3 each)
  const point_id* image_of = nullptr;       ///< per image: its point
  const std::int32_t* image_shift = nullptr;  ///< per image: its shift G (3 each)
  std::size_t points = 0;
  /// The caller's id of each point when the points were renumbered (null: their own), which
  /// half lists decide by.
  const point_id* names = nullptr;

  HORIZON_HOST_DEVICE point_id name(point_id k) const { return names ? names[k] : k; }
};

/// Candidate k of row i as an entry: its point j, its shift S = G - w_j + w_i (x = wrapped +
/// w . cell, G = 0 for the wrapped points), D and the metric's accumulated distance, measured on
/// the caller's coordinates.
template <int D, Metric M>
HORIZON_HOST_DEVICE inline void candidate_entry(point_id k, point_id i, const ImageTables& t, const CellFrame& frame,
                                                CellEntry& e) {
  const bool image = static_cast<std::size_t>(k) >= t.points;
  const std::size_t at = image ? static_cast<std::size_t>(k) - t.points : 0;
  e.j = image ? t.image_of[at] : k;
  const std::int32_t* wi = t.wraps + static_cast<std::size_t>(i) * 3;
  const std::int32_t* wj = t.wraps + static_cast<std::size_t>(e.j) * 3;
  for (int a = 0; a < 3; ++a) e.shift[a] = (image ? t.image_shift[at * 3 + a] : 0) - wj[a] + wi[a];
  measure<D, M>(t.original + static_cast<std::size_t>(i) * D, t.original + static_cast<std::size_t>(e.j) * D, frame, e);
}

/// i itself at shift 0 (self_interaction).
template <int D, Metric M>
HORIZON_HOST_DEVICE inline void self_entry(point_id i, const ImageTables& t, const CellFrame& frame, CellEntry& e) {
  e = CellEntry{};
  e.j = i;
  const double* xi = t.original + static_cast<std::size_t>(i) * D;
  measure<D, M>(xi, xi, frame, e);
}

/// Walks row i of the engine's list (`length` candidates, ascending) in (j, S) order: the
/// wrapped points' part (ascending j) and the images' part (ascending (j, G), so ascending
/// (j, S)) merged, each candidate measured on the caller's coordinates and kept when its
/// accumulated distance is below threshold(i, j) and keeps_entry() agrees on the caller's ids;
/// `emit(entry, position)` gets each, j numbered as the points are in `t`, with the candidate's
/// position in the row (-1: i itself at shift 0, which is no candidate).
template <int D, Metric M, class Threshold, class Emit>
HORIZON_HOST_DEVICE void walk_row(const point_id* row, std::size_t length, point_id i, const ImageTables& t,
                                  const CellFrame& frame, const Threshold& threshold, bool half,
                                  bool self_interaction, Emit&& emit) {
  std::size_t split = 0, past = length;  // the first image: a binary search
  while (split < past) {
    const std::size_t middle = split + (past - split) / 2;
    if (static_cast<std::size_t>(row[middle]) < t.points) split = middle + 1;
    else past = middle;
  }
  auto candidate = [&](point_id k, CellEntry& e) {
    candidate_entry<D, M>(k, i, t, frame, e);
    return e.accumulated < threshold(i, e.j) && keeps_entry(t.name(i), t.name(e.j), e.shift, half, self_interaction);
  };
  // Candidates are points in the caller's order, scattered in memory when that order is not
  // spatial: on the CPU their coordinates and wraps are asked for a few candidates ahead.
  auto prefetch = [&]([[maybe_unused]] std::size_t at) {
#ifndef __CUDA_ARCH__
    constexpr std::size_t ahead = 8;
    if (at + ahead >= length) return;
    const point_id k = row[at + ahead];
    const std::size_t j = static_cast<std::size_t>(k) < t.points ? static_cast<std::size_t>(k)
                                                                  : static_cast<std::size_t>(t.image_of[k - t.points]);
    __builtin_prefetch(t.original + j * D);
    __builtin_prefetch(t.wraps + j * 3);
#endif
  };
  // The next kept candidate of each part (false: none); i itself at S = 0 joins the first part.
  bool self_pending = self_interaction;
  auto next_home = [&](std::size_t& at, CellEntry& e) {
    for (; at < split; ++at) {
      prefetch(at);
      if (self_pending && row[at] > i) break;
      if (candidate(row[at], e)) {
        ++at;
        return true;
      }
    }
    if (self_pending) {
      self_pending = false;
      self_entry<D, M>(i, t, frame, e);
      return true;
    }
    return false;
  };
  auto next_image = [&](std::size_t& at, CellEntry& e) {
    for (; at < length; ++at) {
      prefetch(at);
      if (candidate(row[at], e)) {
        ++at;
        return true;
      }
    }
    return false;
  };
  std::size_t home_at = 0, image_at = split;
  CellEntry home, image;
  bool has_home = next_home(home_at, home), has_image = next_image(image_at, image);
  // Past each next_*(), at is one after the kept candidate. The engine's rows never hold i
  // itself, so a home entry of j = i is the self entry.
  auto home_position = [&] { return home.j == i ? std::int64_t{-1} : static_cast<std::int64_t>(home_at) - 1; };
  while (has_home || has_image) {
    if (has_home && (!has_image || entry_before(home, image))) {
      emit(home, home_position());
      has_home = next_home(home_at, home);
    } else {
      emit(image, static_cast<std::int64_t>(image_at) - 1);
      has_image = next_image(image_at, image);
    }
  }
}

}  // namespace horizon::detail
