#include "proxima/scene/material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace proxima {
namespace {

// 2 × 1 texture: left texel red, right texel blue.
Texture two_texels() {
  Texture t;
  t.image = ImageF(2, 1, 3, 0.0f);
  t.image.at(0, 0, 0) = 1.0f;
  t.image.at(1, 0, 2) = 1.0f;
  return t;
}

TEST(Material, SampleTextureRepeatsAndInterpolates) {
  const Texture t = two_texels();
  EXPECT_EQ(sample_texture(t, {0.25f, 0.5f}), vec3(1, 0, 0));  // left texel center
  EXPECT_EQ(sample_texture(t, {0.75f, 0.5f}), vec3(0, 0, 1));  // right texel center
  EXPECT_EQ(sample_texture(t, {1.25f, 7.5f}), vec3(1, 0, 0));  // repeat wrapping
  EXPECT_EQ(sample_texture(t, {-0.25f, 0.5f}), vec3(0, 0, 1));
}

// uvs of 1e10 or NaN (from files, or interpolation that overflows) must not reach an
// out-of-range float → int conversion — UB (float-cast-overflow under UBSan).
TEST(Material, SampleTextureWithHugeOrNonFiniteUvStaysInRange) {
  const Texture t = two_texels();
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  for (vec2 uv : {vec2(1e10f, 0.5f), vec2(-3e38f, 1e20f), vec2(nan, 0.5f), vec2(0.5f, inf), vec2(-inf, nan)}) {
    const vec3 c = sample_texture(t, uv);
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(c[k] >= 0.0f && c[k] <= 1.0f) << uv.x << " " << uv.y;
  }
  EXPECT_EQ(sample_texture(t, {nan, nan}), sample_texture(t, {0.0f, 0.0f}));  // non-finite reads uv 0
}

}  // namespace
}  // namespace proxima
