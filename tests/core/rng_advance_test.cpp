// Pcg32::advance against the calls it replaces: the reflection frame skips the reference
// renderer's area-light draws with it, so a wrong jump would shift every glossy lobe.
#include <gtest/gtest.h>

#include "proxima/core/rng.h"

namespace proxima {

TEST(Pcg32Advance, EqualsThatManyDraws) {
  for (uint64_t seed : {uint64_t(0), uint64_t(1), uint64_t(0x853C49E6748FEA9Bull), derive_seed(7, 3, 1)})
    for (uint64_t delta : {0ull, 1ull, 2ull, 31ull, 32ull, 33ull, 64ull, 1000ull, 8191ull}) {
      Pcg32 drawn(seed), jumped(seed);
      for (uint64_t i = 0; i < delta; ++i) drawn.next_float();
      jumped.advance(delta);
      for (int i = 0; i < 4; ++i) ASSERT_EQ(drawn.next_u32(), jumped.next_u32()) << "seed " << seed << " delta " << delta;
    }
}

TEST(Pcg32Advance, StreamsDifferInTheJump) {
  Pcg32 a(5, 1), b(5, 2), a_drawn(5, 1);
  a.advance(100);
  b.advance(100);
  for (int i = 0; i < 100; ++i) a_drawn.next_u32();
  EXPECT_EQ(a.next_u32(), a_drawn.next_u32());
  EXPECT_NE(a.next_u32(), b.next_u32());
}

}  // namespace proxima
