#pragma once
/// \file batched_search.hpp
/// The neighbour list handed over in batches of whole rows, for lists larger than memory (the
/// CLI streams them into its output files): one batch of ids is held at a time, plus the
/// offsets of every row, which the count pass gives before the first batch is filled.
#include <cstdint>
#include <functional>

#include "horizon/search.hpp"

namespace horizon {

/// Receives a list batch by batch, in row order.
struct RowBatchSink {
  /// Once, before the first batch: every row's offset (points + 1 of them, as NeighborList::offsets).
  std::function<void(const std::int64_t* offsets, std::size_t points)> begin;
  /// Rows [first, last) and their ids, offsets[last] - offsets[first] of them.
  std::function<void(std::size_t first, std::size_t last, const point_id* ids)> rows;
};

/// search(points, options) delivered to `sink` in batches of at most `batch_entries` ids (a row
/// longer than that goes alone); the rows are the same as search's. CPU backends only (serial,
/// openmp; automatic means openmp), one point set, no periodic box: Error otherwise. Each batch
/// fills the cells holding one of its rows' points: input in lattice or space-filling order pays
/// little for many batches, input in random order up to a fill pass over every cell per batch.
void search_in_batches(PointView points, const SearchOptions& options, std::int64_t batch_entries,
                       const RowBatchSink& sink, SearchStats* stats = nullptr);

}  // namespace horizon
