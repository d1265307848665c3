// SPDX-License-Identifier: BSD-3-Clause
// Progress and interruption (issue 8: a stop request is heard within a
// second): ProgressRange::forBlocks covers its range once, in order, within
// its block limits, and a stop between blocks ends the pass.
#include "volrad/Error.h"
#include "volrad/Progress.h"

#include <gtest/gtest.h>

#include <vector>

using namespace volrad;

TEST(Progress, BlocksCoverTheRangeOnceInOrderWithinTheirLimits)
{
  std::vector<double> reported;
  const ProgressCallback cb = [&](double f) {
    reported.push_back(f);
    return true;
  };
  const ProgressRange range(cb, 0.2, 0.6);
  std::vector<int> seen(100000, 0);
  std::int64_t next = 0, largest = 0, blocks = 0;
  range.forBlocks(std::int64_t(seen.size()), 10, 1000, [&](std::int64_t b0, std::int64_t b1) {
    EXPECT_EQ(b0, next); // consecutive
    EXPECT_LT(b0, b1);
    if (blocks == 0) {
      EXPECT_EQ(b1 - b0, 10); // the first block
    }
    largest = std::max(largest, b1 - b0);
    for (std::int64_t i = b0; i < b1; ++i) {
      ++seen[i];
    }
    next = b1;
    ++blocks;
  });
  EXPECT_EQ(next, std::int64_t(seen.size()));
  for (int s : seen) {
    ASSERT_EQ(s, 1);
  }
  EXPECT_LE(largest, 1000);
  // Cheap items: the blocks grow to the limit, so about n / maxBlock of them.
  EXPECT_LT(blocks, 200);
  ASSERT_EQ(reported.size(), std::size_t(blocks)); // one report per block
  for (std::size_t i = 1; i < reported.size(); ++i) {
    EXPECT_GT(reported[i], reported[i - 1]);
  }
  EXPECT_GT(reported.front(), 0.2);
  EXPECT_DOUBLE_EQ(reported.back(), 0.6);
}

TEST(Progress, AStopBetweenBlocksEndsThePass)
{
  int reports = 0;
  const ProgressCallback cb = [&](double) { return ++reports < 3; };
  const ProgressRange range(cb, 0.0, 1.0);
  int calls = 0;
  EXPECT_THROW(range.forBlocks(1000, 10, 10, [&](std::int64_t, std::int64_t) { ++calls; }),
               Aborted);
  EXPECT_EQ(calls, 3); // the third report said stop: no fourth block
  // An empty pass reports nothing and calls nothing.
  reports = 0;
  range.forBlocks(0, 10, 10, [&](std::int64_t, std::int64_t) { ++calls; });
  EXPECT_EQ(reports, 0);
  EXPECT_EQ(calls, 3);
}
