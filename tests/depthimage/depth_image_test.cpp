// DepthImage: reprojection agrees with project(unproject()), maps a camera onto itself.
#include "proxima/depthimage/depth_image.h"

#include <gtest/gtest.h>

#include <bit>

#include "proxima/core/rng.h"

#include "figure11.h"

namespace proxima {
namespace {

TEST(DepthImage, ReprojectionOntoItselfKeepsThePixel) {
  const Camera c = look_at(vec3(1, 2, 5), vec3(0), vec3(0, 1, 0), 50.0f, 640, 480);
  const Reprojection r(c, c);
  for (int y = 0; y < 480; y += 7) {
    for (int x = 0; x < 640; x += 5) {
      vec2 p;
      float d;
      ASSERT_TRUE(r.map(x, y, 3.7f, p, d));
      int rx, ry;
      ASSERT_TRUE(pixel_in(c, p, rx, ry));
      EXPECT_EQ(rx, x);
      EXPECT_EQ(ry, y);
      EXPECT_NEAR(d, 3.7f, 1e-5f);
    }
  }
}

TEST(DepthImage, ReprojectionMatchesUnprojectThenProject) {
  const Camera a = look_at(vec3(1, 2, 5), vec3(0), vec3(0, 1, 0), 50.0f, 320, 240);
  const Camera b = look_at(vec3(-2, 1, 4), vec3(0.5f, 0, 0), vec3(0, 1, 0), 35.0f, 200, 300);
  const Reprojection r(a, b);
  for (int y = 0; y < 240; y += 13) {
    for (int x = 0; x < 320; x += 11) {
      const float d = 2.0f + 0.01f * float(x + y);
      const auto want = project(b, unproject(a, vec2(float(x) + 0.5f, float(y) + 0.5f), d));
      vec2 p;
      float depth;
      ASSERT_EQ(r.map(x, y, d, p, depth), want.has_value());
      EXPECT_NEAR(p.x, want->pixel.x, 2e-3f);
      EXPECT_NEAR(p.y, want->pixel.y, 2e-3f);
      EXPECT_NEAR(depth, want->depth, 1e-4f);
    }
  }
}

// map4 and pixel4 (the redundancy test's four-lane forms) must give map()'s bits: the pixel
// redundancy test compares the truncated pixel, so any last-bit difference could flip a
// sample. Random pixels and depths, target cameras in front, beside and behind.
TEST(DepthImage, MapFourAndPixelFourAreBitIdenticalToMap) {
  const Camera a = look_at(vec3(1, 2, 5), vec3(0), vec3(0, 1, 0), 50.0f, 1024, 768);
  const Camera targets[] = {look_at(vec3(1.3f, 2.1f, 4.9f), vec3(0.1f, 0, 0), vec3(0, 1, 0), 50.0f, 1024, 1024),
                            look_at(vec3(-4, 1, 0), vec3(0), vec3(0, 1, 0), 35.0f, 200, 300),
                            look_at(vec3(0, 0, -5), vec3(0, 0, -10), vec3(0, 1, 0), 60.0f, 64, 64)};
  Pcg32 rng(17);
  size_t mapped = 0, unmapped = 0, inside = 0;
  for (const Camera& b : targets) {
    const Reprojection r(a, b);
    for (int trial = 0; trial < 20000; ++trial) {
      const int y = int(rng.next_u32() % 768u);
      int x[4];
      float d[4];
      for (int k = 0; k < 4; ++k) {
        x[k] = int(rng.next_u32() % 1024u);
        d[k] = 0.05f + 20.0f * rng.next_float();
      }
      float px[4], py[4];
      const unsigned ok = r.map4(x, y, d, px, py);
      uint32_t at[4];
      const unsigned in = r.pixel4(x, y, d, b.width, b.height, at);
      for (int k = 0; k < 4; ++k) {
        vec2 p;
        float depth;
        const bool want = r.map(x[k], y, d[k], p, depth);
        ASSERT_EQ(((ok >> k) & 1u) != 0, want) << trial;
        // pixel4 = map() then pixel_in(), as the scalar redundancy test does.
        int rx = 0, ry = 0;
        const bool want_in = want && pixel_in(b, p, rx, ry);
        ASSERT_EQ(((in >> k) & 1u) != 0, want_in) << trial;
        if (want_in) {
          ++inside;
          ASSERT_EQ(at[k], uint32_t(ry * b.width + rx)) << trial;
        }
        if (!want) {
          ++unmapped;
          continue;
        }
        ++mapped;
        ASSERT_EQ(std::bit_cast<uint32_t>(px[k]), std::bit_cast<uint32_t>(p.x)) << trial;
        ASSERT_EQ(std::bit_cast<uint32_t>(py[k]), std::bit_cast<uint32_t>(p.y)) << trial;
      }
    }
  }
  EXPECT_GT(mapped, 100000u);
  EXPECT_GT(unmapped, 10000u);
  EXPECT_GT(inside, 10000u);
  EXPECT_GT(mapped - inside, 10000u);  // mapped but outside the target image
}

TEST(DepthImage, BehindTheTargetCameraIsNotMapped) {
  const Camera a = look_at(vec3(0, 0, 5), vec3(0), vec3(0, 1, 0), 50.0f, 64, 64);
  const Camera b = look_at(vec3(0, 0, -5), vec3(0, 0, -10), vec3(0, 1, 0), 50.0f, 64, 64);
  vec2 p;
  float d;
  EXPECT_FALSE(Reprojection(a, b).map(32, 32, 5.0f, p, d));  // the origin is behind b
}

TEST(DepthImage, ShadedImageHasNormalsAndColorWhereItHasSamples) {
  const Scene scene = figure11::scene();
  const DepthImage image = render_depth_image(scene, corner_camera(figure11::views(64), 0), true);
  const size_t n = sample_count(image);
  EXPECT_GT(n, 1000u);
  EXPECT_LT(n, 64u * 64u);  // sky above and below the slabs
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (image.triangle.at(x, y) == kNoTriangle) {
        EXPECT_EQ(image.depth.at(x, y), kInf);
        continue;
      }
      EXPECT_NEAR(glm::length(vec3(image.normal.at(x, y, 0), image.normal.at(x, y, 1), image.normal.at(x, y, 2))),
                  1.0f, 1e-4f);
      const vec3 p = sample_point(image, x, y);
      EXPECT_NEAR(-world_to_camera(image.camera, p).z, image.depth.at(x, y), 1e-4f);
    }
  }
}

}  // namespace
}  // namespace proxima
