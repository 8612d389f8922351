#pragma once
/// \file block_filter.hpp
/// Peridigm's block rules: every point belongs to a block (an integer id), and only bonds
/// between blocks named in a list of pairs are kept; e.g. two bodies in contact that must not
/// bond across their interface interact through the pairs 1-1 and 2-2 only.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "horizon/neighbor_list.hpp"

namespace horizon {

/// Unordered pairs of block ids whose points interact (1-2 also allows 2-1).
struct BlockPairs {
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  /// From "1-1,1-2,2-2" (ids >= 0); Error naming the item that is not a pair otherwise.
  static BlockPairs parse(const std::string& text);
};

/// `list` without the bonds i-j whose blocks {row_blocks[i], column_blocks[j]} are not one of
/// `pairs`; rows keep their order. `column_blocks` gives the block of every point the ids index
/// (a query list's references); the overload without it is for a list of one point set.
/// Error when the row blocks do not match the list, or a pair names a block no point is in. A
/// list passed with std::move is filtered in its own arrays.
NeighborList filter_blocks(NeighborList list, const std::vector<std::int32_t>& row_blocks,
                           const std::vector<std::int32_t>& column_blocks, const BlockPairs& pairs, int threads = 0);
NeighborList filter_blocks(NeighborList list, const std::vector<std::int32_t>& blocks, const BlockPairs& pairs,
                           int threads = 0);

}  // namespace horizon
