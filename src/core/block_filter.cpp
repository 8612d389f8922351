#include "horizon/block_filter.hpp"

#include <omp.h>

#include <algorithm>
#include <charconv>

#include "select_entries.hpp"
#include "horizon/error.hpp"

namespace horizon {

namespace {

bool parse_id(std::string_view text, std::int32_t& id) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), id);
  return error == std::errc() && end == text.data() + text.size() && id >= 0;
}

std::string list_of(const std::vector<std::int32_t>& ids) {
  std::string text;
  for (std::size_t b = 0; b < ids.size() && b < 20; ++b) text += (b ? ", " : "") + std::to_string(ids[b]);
  return ids.size() > 20 ? text + ", ..." : text;
}

}  // namespace

BlockPairs BlockPairs::parse(const std::string& text) {
  BlockPairs result;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string_view item = std::string_view(text).substr(at, comma - at);
    const std::size_t dash = item.find('-');
    std::int32_t a = -1, b = -1;
    if (dash == std::string_view::npos || !parse_id(item.substr(0, dash), a) || !parse_id(item.substr(dash + 1), b))
      throw Error("block pairs " + text + ": '" + std::string(item) + "' is not a pair of block ids such as 1-2");
    result.pairs.emplace_back(a, b);
    at = comma + 1;
  }
  return result;
}

NeighborList filter_blocks(NeighborList list, const std::vector<std::int32_t>& row_blocks,
                           const std::vector<std::int32_t>& column_blocks, const BlockPairs& pairs, int threads) {
  if (row_blocks.size() != list.size())
    throw Error("blocks: " + std::to_string(row_blocks.size()) + " block ids for " + std::to_string(list.size()) +
                " points");
  // Blocks renumbered densely, so the pairs become a small table.
  const bool one_set = &row_blocks == &column_blocks;
  std::vector<std::int32_t> ids(row_blocks);
  if (!one_set) ids.insert(ids.end(), column_blocks.begin(), column_blocks.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const std::size_t count = ids.size();
  auto dense = [&](std::int32_t id) { return static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin()); };
  std::vector<char> allowed(count * count, 0);
  for (const auto& [a, b] : pairs.pairs)
    for (std::int32_t id : {a, b})
      if (!std::binary_search(ids.begin(), ids.end(), id))
        throw Error("block pair " + std::to_string(a) + "-" + std::to_string(b) + ": no point is in block " +
                    std::to_string(id) + " (blocks: " + list_of(ids) + ")");
  for (const auto& [a, b] : pairs.pairs) allowed[dense(a) * count + dense(b)] = allowed[dense(b) * count + dense(a)] = 1;
  std::vector<char> allows_all(count);
  for (std::size_t a = 0; a < count; ++a)
    allows_all[a] = std::all_of(allowed.begin() + static_cast<std::ptrdiff_t>(a * count),
                                allowed.begin() + static_cast<std::ptrdiff_t>((a + 1) * count), [](char c) { return c != 0; });
  std::vector<std::uint32_t> row_block(row_blocks.size()), column_block;
  std::transform(row_blocks.begin(), row_blocks.end(), row_block.begin(), dense);
  if (one_set) {
    column_block = row_block;
  } else {
    column_block.resize(column_blocks.size());
    std::transform(column_blocks.begin(), column_blocks.end(), column_block.begin(), dense);
  }
  return detail::select_entries(
      std::move(list), [&](std::size_t i) { return allows_all[row_block[i]] != 0; },
      [&](std::size_t i, point_id j) { return allowed[row_block[i] * count + column_block[static_cast<std::size_t>(j)]] != 0; },
      threads > 0 ? threads : omp_get_max_threads());
}

NeighborList filter_blocks(NeighborList list, const std::vector<std::int32_t>& blocks, const BlockPairs& pairs,
                           int threads) {
  return filter_blocks(std::move(list), blocks, blocks, pairs, threads);
}

}  // namespace horizon
