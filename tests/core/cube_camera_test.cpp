#include "proxima/core/cube_camera.h"

#include <gtest/gtest.h>

#include "proxima/core/rng.h"

namespace proxima {
namespace {

TEST(CubeCamera, LookupAgreesWithFaceCameraProjection) {
  CubeCamera cube;
  cube.center = {1.0f, -2.0f, 0.5f};
  cube.resolution = 128;
  Pcg32 rng(7);
  for (int i = 0; i < 2000; ++i) {
    vec3 dir(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
    if (glm::length(dir) < 1e-3f) continue;
    CubeTexel t = cube_lookup(cube, dir);
    auto p = project(face_camera(cube, t.face), cube.center + dir);
    ASSERT_TRUE(p.has_value());
    EXPECT_NEAR(p->pixel.x, t.pixel.x, 1e-2f);
    EXPECT_NEAR(p->pixel.y, t.pixel.y, 1e-2f);
    EXPECT_GE(t.pixel.x, -1e-3f);
    EXPECT_LE(t.pixel.x, 128.001f);
  }
}

TEST(CubeCamera, AxesLandOnTheirFacesCenters) {
  CubeCamera cube;
  cube.resolution = 64;
  vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    CubeTexel t = cube_lookup(cube, axes[f]);
    EXPECT_EQ(t.face, f);
    EXPECT_NEAR(t.pixel.x, 32.0f, 1e-4f);
    EXPECT_NEAR(t.pixel.y, 32.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(camera_forward(face_camera(cube, f)), axes[f]), 1.0f, 1e-6f);
  }
}

}  // namespace
}  // namespace proxima
