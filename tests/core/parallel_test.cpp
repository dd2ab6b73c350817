#include "proxima/core/parallel.h"

#include <atomic>
#include <vector>

#include <gtest/gtest.h>

namespace proxima {
namespace {

TEST(Parallel, TilesCoverEveryPixelOnce) {
  for (int threads : {1, 2}) {
    ThreadLimit limit(threads);
    std::vector<std::atomic<int>> count(size_t(37 * 23));
    parallel_for_tiles(37, 23, 8, [&](const Tile& t) {
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) count[size_t(y * 37 + x)]++;
    });
    for (auto& c : count) EXPECT_EQ(c.load(), 1);
  }
}

TEST(Parallel, ThreadLimitIsApplied) {
  {
    ThreadLimit limit(1);
    EXPECT_EQ(active_threads(), 1);
  }
  EXPECT_GE(active_threads(), 1);
}

TEST(Parallel, ForCoversRangeOnce) {
  std::vector<std::atomic<int>> count(1000);
  parallel_for(1000, 7, [&](size_t b, size_t e) {
    EXPECT_LE(e - b, 7u);
    for (size_t i = b; i < e; ++i) count[i]++;
  });
  for (auto& c : count) EXPECT_EQ(c.load(), 1);
}

}  // namespace
}  // namespace proxima
