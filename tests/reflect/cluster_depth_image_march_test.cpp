#include <gtest/gtest.h>

#include "proxima/core/rng.h"
#include "proxima/reflect/depth_image_march.h"

namespace proxima {

namespace {

const Camera kCamera = look_at(vec3(0.0f), vec3(0, 0, -1), vec3(0, 1, 0), 60.0f, 128, 128, 0.1f, 100.0f);

// Depth image of the plane dot(x, n) = c, seen by kCamera at pixel centres.
ImageF plane_depth(vec3 n, float c) {
  ImageF d(kCamera.width, kCamera.height, 1, kInf);
  for (int y = 0; y < d.height(); ++y)
    for (int x = 0; x < d.width(); ++x) {
      Ray r = ray_through(kCamera, vec2(float(x) + 0.5f, float(y) + 0.5f));
      float t = c / glm::dot(r.dir, n);
      if (t > 0.0f) d.at(x, y) = -world_to_camera(kCamera, r.origin + t * r.dir).z;
    }
  return d;
}

}  // namespace

TEST(ClusterDepthImageMarch, FindsTheAnalyticHitOnATiltedPlane) {
  const vec3 n = glm::normalize(vec3(0.1f, 0.3f, 1.0f));
  const float c = glm::dot(n, vec3(0, 0, -6));
  const ImageF depth = plane_depth(n, c);
  const vec3 begin(0.8f, -0.4f, -1.0f);
  for (vec3 dir : {vec3(-0.3f, 0.2f, -1.0f), vec3(0.1f, 0.1f, -1.0f), vec3(-0.05f, 0.25f, -1.0f)}) {
    dir = glm::normalize(dir);
    const float t = (c - glm::dot(n, begin)) / glm::dot(n, dir);
    const vec3 analytic = begin + t * dir;
    auto hit = march_depth_image(kCamera, depth, begin, begin + 2.0f * t * dir);
    ASSERT_TRUE(hit.has_value());
    const vec3 found = unproject(kCamera, hit->pixel, hit->depth);
    // Within one texel footprint at depth 6 (≈ 0.054 m) of the analytic point.
    EXPECT_LT(glm::length(found - analytic), 0.06f) << found.x << " " << found.y << " " << found.z;
  }
}

TEST(ClusterDepthImageMarch, RayEndingInFrontOfTheSurfaceMisses) {
  const ImageF depth = plane_depth(vec3(0, 0, 1), -6.0f);
  auto hit = march_depth_image(kCamera, depth, vec3(0.5f, 0.0f, -1.0f), vec3(-1.0f, 0.5f, -5.5f));
  EXPECT_FALSE(hit.has_value());
}

TEST(ClusterDepthImageMarch, RayPassingBehindAnObjectMissesIt) {
  // Back wall at depth 10 with a near plate at depth 3 over texels [40, 88)².
  ImageF depth = plane_depth(vec3(0, 0, 1), -10.0f);
  for (int y = 40; y < 88; ++y)
    for (int x = 40; x < 88; ++x) depth.at(x, y) = 3.0f;
  // Across the plate from left to right at depth 6 → 8, ending before the wall.
  const vec3 a = unproject(kCamera, vec2(10.5f, 64.5f), 6.0f), b = unproject(kCamera, vec2(120.5f, 64.5f), 8.0f);
  EXPECT_FALSE(march_depth_image(kCamera, depth, a, b).has_value());
  // With fill_behind it reports the wall it was last in front of, at the plate's edge.
  MarchOptions fill;
  fill.fill_behind = true;
  auto filled = march_depth_image(kCamera, depth, a, b, fill);
  ASSERT_TRUE(filled.has_value());
  EXPECT_TRUE(filled->filled);
  EXPECT_FLOAT_EQ(filled->depth, 10.0f);
  EXPECT_NEAR(filled->pixel.x, 40.0f, 1.5f);
  // The same ray continued to depth 12 hits the wall, right of the plate.
  const vec3 c = unproject(kCamera, vec2(120.5f, 64.5f), 12.0f);
  auto wall = march_depth_image(kCamera, depth, a, c);
  ASSERT_TRUE(wall.has_value());
  EXPECT_NEAR(wall->depth, 10.0f, 0.05f);
  EXPECT_GE(wall->pixel.x, 88.0f);
  // A ray that goes from depth 2 to 4 inside the plate's footprint hits the plate.
  auto plate = march_depth_image(kCamera, depth, unproject(kCamera, vec2(50.5f, 60.5f), 2.0f),
                                 unproject(kCamera, vec2(70.5f, 62.5f), 4.0f));
  ASSERT_TRUE(plate.has_value());
  EXPECT_FLOAT_EQ(plate->depth, 3.0f);
}

TEST(ClusterDepthImageMarch, SegmentBehindTheCameraOrOutsideTheImage) {
  const ImageF depth = plane_depth(vec3(0, 0, 1), -6.0f);
  EXPECT_FALSE(march_depth_image(kCamera, depth, vec3(0, 0, 1), vec3(0, 0, -8)).has_value());
  EXPECT_FALSE(march_depth_image(kCamera, depth, vec3(20, 0, -2), vec3(30, 0, -8)).has_value());
}

TEST(ClusterDepthImageMarch, BlockSkippingGivesTheSameHits) {
  // A back wall with random plates in front of it and empty texels: the march with block
  // minima must return exactly what the texel-by-texel march returns.
  ImageF depth = plane_depth(glm::normalize(vec3(0.2f, -0.1f, 1.0f)), -10.0f);
  Pcg32 rng(7);
  for (int p = 0; p < 12; ++p) {
    const int x0 = int(rng.next_float() * 110.0f), y0 = int(rng.next_float() * 110.0f);
    const int size = 3 + int(rng.next_float() * 20.0f);
    const float z = 2.0f + 6.0f * rng.next_float();
    for (int y = y0; y < std::min(128, y0 + size); ++y)
      for (int x = x0; x < std::min(128, x0 + size); ++x) depth.at(x, y) = p % 4 == 3 ? kInf : z;
  }
  for (int block : {4, 8, 16}) {
    const ImageF minima = depth_block_min(depth, block);
    ASSERT_EQ(minima.width(), (128 + block - 1) / block);
    int hits = 0;
    for (int r = 0; r < 400; ++r) {
      const vec2 a(rng.next_float() * 128.0f, rng.next_float() * 128.0f), b(rng.next_float() * 128.0f, rng.next_float() * 128.0f);
      const vec3 begin = unproject(kCamera, a, 0.5f + 2.0f * rng.next_float());
      const vec3 end = unproject(kCamera, b, 4.0f + 10.0f * rng.next_float());
      MarchOptions plain, skipping;
      plain.fill_behind = skipping.fill_behind = (r % 2) == 0;
      skipping.block_min = &minima;
      skipping.block = block;
      const auto x = march_depth_image(kCamera, depth, begin, end, plain);
      const auto y = march_depth_image(kCamera, depth, begin, end, skipping);
      ASSERT_EQ(x.has_value(), y.has_value()) << "ray " << r;
      if (!x) continue;
      ++hits;
      EXPECT_EQ(x->pixel, y->pixel) << "ray " << r;
      EXPECT_EQ(x->depth, y->depth) << "ray " << r;
      EXPECT_EQ(x->filled, y->filled) << "ray " << r;
    }
    EXPECT_GT(hits, 100);
  }
}

TEST(ClusterDepthImageMarch, FourStepsAtATimeGiveTheSameHits) {
  // A tilted wall, random plates in front of it (some empty), and a noisy strip whose
  // neighbouring texels are sometimes continuous and sometimes not: the batched march must
  // return exactly what the step-by-step march returns, with and without fill, for long
  // and short segments (short ones end inside a batch), and for segments that start
  // behind a surface.
  ImageF depth = plane_depth(glm::normalize(vec3(-0.3f, 0.2f, 1.0f)), -12.0f);
  Pcg32 rng(11);
  for (int p = 0; p < 16; ++p) {
    const int x0 = int(rng.next_float() * 120.0f), y0 = int(rng.next_float() * 120.0f);
    const int size = 2 + int(rng.next_float() * 24.0f);
    const float z = 1.5f + 7.0f * rng.next_float();
    for (int y = y0; y < std::min(128, y0 + size); ++y)
      for (int x = x0; x < std::min(128, x0 + size); ++x) depth.at(x, y) = p % 5 == 4 ? kInf : z;
  }
  for (int y = 60; y < 68; ++y)
    for (int x = 0; x < 128; ++x) depth.at(x, y) = 5.0f + 0.6f * rng.next_float();
  int hits = 0, fills = 0, misses = 0;
  for (int r = 0; r < 3000; ++r) {
    const vec2 a(rng.next_float() * 140.0f - 6.0f, rng.next_float() * 140.0f - 6.0f);
    const vec2 b = r % 3 == 0 ? a + vec2(rng.next_float() * 8.0f - 4.0f, rng.next_float() * 8.0f - 4.0f)
                              : vec2(rng.next_float() * 140.0f - 6.0f, rng.next_float() * 140.0f - 6.0f);
    const vec3 begin = unproject(kCamera, a, 0.3f + 6.0f * rng.next_float());
    const vec3 end = unproject(kCamera, b, 2.0f + 14.0f * rng.next_float());
    MarchOptions batched, single;
    batched.fill_behind = single.fill_behind = (r % 2) == 0;
    single.batch = false;
    const auto x = march_depth_image(kCamera, depth, begin, end, batched);
    const auto y = march_depth_image(CameraProjection(kCamera), depth, begin, end, single);
    ASSERT_EQ(x.has_value(), y.has_value()) << "ray " << r;
    if (!x) {
      ++misses;
      continue;
    }
    x->filled ? ++fills : ++hits;
    EXPECT_EQ(x->pixel, y->pixel) << "ray " << r;
    EXPECT_EQ(x->depth, y->depth) << "ray " << r;
    EXPECT_EQ(x->filled, y->filled) << "ray " << r;
  }
  // The rays exercise all three outcomes.
  EXPECT_GT(hits, 500);
  EXPECT_GT(fills, 50);
  EXPECT_GT(misses, 50);
}

}  // namespace proxima
