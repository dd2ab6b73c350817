// core/range_check.h: the one-line messages every option range shares, and where the
// bounds fall (inclusive, exclusive, NaN).
#include "proxima/core/range_check.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "test_util.h"

namespace proxima {
namespace {

TEST(RangeCheck, IntegersPassInsideAndAtTheBounds) {
  for (int v : {1, 2, 64}) EXPECT_EQ(error_of([&] { require_in_range(v, 1, 64, "--light-samples"); }), "") << v;
  EXPECT_EQ(error_of([&] { require_in_range(0, 1, 64, "--light-samples"); }), "--light-samples: must be in 1..64");
  EXPECT_EQ(error_of([&] { require_in_range(65, 1, 64, "--light-samples"); }), "--light-samples: must be in 1..64");
}

TEST(RangeCheck, NoteFollowsTheRange) {
  EXPECT_EQ(error_of([&] { require_in_range(17, 0, 16, "--move-scale", "(0 = adaptive)"); }),
            "--move-scale: must be in 0..16 (0 = adaptive)");
  EXPECT_EQ(error_of([&] { require_in_range(2000, 1, 1024, "--gloss-rays", "for --method cluster"); }),
            "--gloss-rays: must be in 1..1024 for --method cluster");
}

TEST(RangeCheck, RealNumbersUseIntervalsAndRejectNaN) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(error_of([&] { require_in_range(1.0f, 0.0f, 1.0f, "--threshold"); }), "");
  EXPECT_EQ(error_of([&] { require_in_range(1.5f, 0.0f, 1.0f, "--threshold"); }), "--threshold: must be in [0, 1]");
  EXPECT_EQ(error_of([&] { require_in_range(nan, 0.0f, 1.0f, "--threshold"); }), "--threshold: must be in [0, 1]");
  EXPECT_EQ(error_of([&] { require_in_range(0.02f, 0.0f, 0.01f, "level: seam_jitter", "m"); }),
            "level: seam_jitter: must be in [0, 0.01] m");
  // (lo, hi]: the low bound itself fails.
  EXPECT_EQ(error_of([&] { require_above_at_most(8.0f, 0.0f, 8.0f, "--resolution-scale"); }), "");
  EXPECT_EQ(error_of([&] { require_above_at_most(0.0f, 0.0f, 8.0f, "--resolution-scale"); }),
            "--resolution-scale: must be in (0, 8]");
  EXPECT_EQ(error_of([&] { require_above_at_most(nan, 0.0f, 90.0f, "--angle-step", "degrees"); }),
            "--angle-step: must be in (0, 90] degrees");
  // ≥ lo: infinity passes (an "off" value), NaN fails.
  EXPECT_EQ(error_of([&] { require_at_least(inf, 1.0f, "--spread-limit", "(inf = off)"); }), "");
  EXPECT_EQ(error_of([&] { require_at_least(nan, 1.0f, "--spread-limit", "(inf = off)"); }),
            "--spread-limit: must be ≥ 1 (inf = off)");
}

TEST(RangeCheck, AtLeastOnIntegers) {
  EXPECT_EQ(error_of([&] { require_at_least(-1, -1, "--image-frame"); }), "");
  EXPECT_EQ(error_of([&] { require_at_least(-2, -1, "--image-frame"); }), "--image-frame: must be ≥ -1");
  EXPECT_EQ(error_of([&] { require_at_least(-1, 0, "--threads"); }), "--threads: must be ≥ 0");
}

}  // namespace
}  // namespace proxima
