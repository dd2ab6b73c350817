// glossy_lobe_directions (the cone's constants once per call) against glossy_lobe_direction
// per sample, bit for bit: the reflection frame's rays use the first, the reference renderer
// the second.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "proxima/core/rng.h"
#include "proxima/scene/shading.h"

namespace proxima {

TEST(GlossyLobeDirections, EqualGlossyLobeDirectionBitForBit) {
  Pcg32 rng(11);
  std::vector<vec2> u(9);
  std::vector<vec3> got(9);
  for (int trial = 0; trial < 2000; ++trial) {
    const vec3 mirror = glm::normalize(vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
    // Half the trials with a normal near the mirror's tangent plane, so some rays are folded back.
    vec3 n = glm::normalize(vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
    if (trial % 2) n = glm::normalize(n - 0.95f * glm::dot(n, mirror) * mirror);
    const float half_angle = trial % 7 == 0 ? 0.0f : glossy_lobe_half_angle(rng.next_float());
    stratified_samples_2d(u, rng);
    glossy_lobe_directions(mirror, n, half_angle, u, got);
    for (size_t r = 0; r < u.size(); ++r) {
      const vec3 want = glossy_lobe_direction(mirror, n, half_angle, u[r]);
      ASSERT_EQ(std::memcmp(&want, &got[r], sizeof(vec3)), 0) << "trial " << trial << " ray " << r;
    }
  }
}

}  // namespace proxima
