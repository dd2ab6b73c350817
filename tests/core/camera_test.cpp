#include "proxima/core/camera.h"

#include <gtest/gtest.h>

#include "proxima/core/error.h"

namespace proxima {
namespace {

TEST(Camera, ProjectUnprojectRoundTripAtPixelCenters) {
  Camera cam = look_at({1.0f, 2.0f, 5.0f}, {0.3f, 0.5f, -1.0f}, {0, 1, 0}, 55.0f, 64, 48);
  for (int y = 0; y < cam.height; y += 3) {
    for (int x = 0; x < cam.width; x += 3) {
      vec2 center(float(x) + 0.5f, float(y) + 0.5f);
      for (float depth : {0.05f, 1.0f, 7.5f, 300.0f}) {
        vec3 world = unproject(cam, center, depth);
        auto p = project(cam, world);
        ASSERT_TRUE(p.has_value());
        EXPECT_NEAR(p->pixel.x, center.x, 2e-3f * std::max(1.0f, depth / 10.0f));
        EXPECT_NEAR(p->pixel.y, center.y, 2e-3f * std::max(1.0f, depth / 10.0f));
        EXPECT_NEAR(p->depth, depth, 1e-5f * depth + 1e-5f);
      }
    }
  }
}

TEST(Camera, RayThroughPixelHitsUnprojectedPoint) {
  Camera cam = look_at({0, 1, 3}, {0, 1, 0}, {0, 1, 0}, 40.0f, 100, 80);
  vec2 pixel(17.5f, 63.5f);
  Ray ray = ray_through(cam, pixel);
  vec3 p = unproject(cam, pixel, 2.0f);
  vec3 along = glm::normalize(p - ray.origin);
  EXPECT_NEAR(glm::dot(along, ray.dir), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(ray.dir), 1.0f, 1e-6f);
}

TEST(Camera, ConventionsLookDownMinusZWithRowZeroAtTop) {
  Camera cam;  // at the origin, identity orientation
  cam.width = 10;
  cam.height = 10;
  EXPECT_NEAR(camera_forward(cam).z, -1.0f, 1e-6f);
  auto above = project(cam, {0.0f, 1.0f, -5.0f});
  ASSERT_TRUE(above.has_value());
  EXPECT_LT(above->pixel.y, 5.0f);  // +Y up → smaller row index
  auto right = project(cam, {1.0f, 0.0f, -5.0f});
  EXPECT_GT(right->pixel.x, 5.0f);
  EXPECT_FALSE(project(cam, {0.0f, 0.0f, 1.0f}).has_value());  // behind the camera
}

TEST(Camera, MatricesAgreeWithProject) {
  Camera cam = look_at({2, 3, 4}, {0, 0, 0}, {0, 1, 0}, 60.0f, 80, 60, 0.1f, 100.0f);
  vec3 world(0.3f, -0.2f, 0.5f);
  vec4 clip = projection_matrix(cam) * view_matrix(cam) * vec4(world, 1.0f);
  vec2 ndc(clip.x / clip.w, clip.y / clip.w);
  vec2 pixel((ndc.x * 0.5f + 0.5f) * 80.0f, (0.5f - ndc.y * 0.5f) * 60.0f);
  auto p = project(cam, world);
  EXPECT_NEAR(pixel.x, p->pixel.x, 1e-3f);
  EXPECT_NEAR(pixel.y, p->pixel.y, 1e-3f);
  EXPECT_NEAR(clip.w, p->depth, 1e-4f);
}

TEST(Camera, ValidateRejectsBadResolutionAndClip) {
  Camera cam;
  EXPECT_NO_THROW(validate_camera(cam, "--width"));
  cam.width = 0;
  EXPECT_THROW(validate_camera(cam, "--width"), InputError);
  cam.width = kMaxImageSide + 1;
  EXPECT_THROW(validate_camera(cam, "--width"), InputError);
  cam.width = 64;
  cam.near = 0.0f;
  EXPECT_THROW(validate_camera(cam, "camera"), InputError);
  cam.near = 1.0f;
  cam.vfov_deg = 180.0f;
  EXPECT_THROW(validate_camera(cam, "camera"), InputError);
}

}  // namespace
}  // namespace proxima
