#pragma once
// Unsorted rows hold the same families as sorted ones: the same offsets, and each row equal to
// the sorted row once sorted.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "horizon/neighbor_list.hpp"

namespace horizon::testing {

inline void expect_same_families(const NeighborList& unsorted, const NeighborList& sorted) {
  ASSERT_EQ(unsorted.offsets(), sorted.offsets());
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    std::vector<point_id> row(unsorted.row(i).begin(), unsorted.row(i).end());
    std::sort(row.begin(), row.end());
    ASSERT_TRUE(std::equal(row.begin(), row.end(), sorted.row(i).begin(), sorted.row(i).end())) << "row " << i;
  }
}

}  // namespace horizon::testing
