// The transpose behind the scatter and max radius rules against a plain one: waves of every
// size (one row alone, a few rows, all), any thread count, empty and long rows, many blocks.
#include "core/transpose_rows.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace {

using horizon::point_id;

TEST(TransposeRows, MatchesAPlainTransposeForAnyWaveAndThreadCount) {
  for (const std::int64_t n : {1, 2, 70, 5000, 40000}) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(n));
    horizon::Buffer<std::int64_t> offsets(static_cast<std::size_t>(n) + 1);
    horizon::Buffer<point_id> ids;
    offsets[0] = 0;
    for (std::int64_t i = 0; i < n; ++i) {
      // Mostly short rows, some empty, one in 50 long (a row longer than a wave).
      const std::int64_t length = rng() % 50 == 0 ? std::min<std::int64_t>(n, 300) : static_cast<std::int64_t>(rng() % 8);
      std::vector<point_id> row;
      for (std::int64_t e = 0; e < length; ++e) row.push_back(static_cast<point_id>(rng() % static_cast<std::uint64_t>(n)));
      std::sort(row.begin(), row.end());
      row.erase(std::unique(row.begin(), row.end()), row.end());
      ids.insert(ids.end(), row.begin(), row.end());
      offsets[static_cast<std::size_t>(i) + 1] = static_cast<std::int64_t>(ids.size());
    }
    std::vector<std::vector<point_id>> expected(static_cast<std::size_t>(n));
    for (std::int64_t i = 0; i < n; ++i)
      for (std::int64_t e = offsets[static_cast<std::size_t>(i)]; e < offsets[static_cast<std::size_t>(i) + 1]; ++e)
        expected[static_cast<std::size_t>(ids[static_cast<std::size_t>(e)])].push_back(static_cast<point_id>(i));
    for (const std::int64_t wave : {std::int64_t{1}, std::int64_t{37}, std::int64_t{1000}, std::int64_t{1} << 24})
      for (const int threads : {1, 3, 16}) {
        if (wave < 1000 && n > 5000) continue;  // a parallel region per wave: tens of thousands
        horizon::Buffer<std::int64_t> out_offsets;
        horizon::Buffer<point_id> out_ids;
        horizon::detail::transpose_rows(offsets.data(), ids.data(), n, threads, out_offsets, out_ids, wave);
        ASSERT_EQ(out_offsets.size(), static_cast<std::size_t>(n) + 1);
        ASSERT_EQ(out_offsets[0], 0);
        ASSERT_EQ(out_ids.size(), ids.size());
        for (std::int64_t j = 0; j < n; ++j) {
          const std::vector<point_id> row(out_ids.begin() + out_offsets[static_cast<std::size_t>(j)],
                                          out_ids.begin() + out_offsets[static_cast<std::size_t>(j) + 1]);
          ASSERT_EQ(row, expected[static_cast<std::size_t>(j)]) << "n " << n << " wave " << wave << " threads "
                                                                << threads << " row " << j;
        }
      }
  }
}

}  // namespace
