#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "proxima/reflect/cluster_camera.h"
#include "proxima/scene/shading.h"

namespace proxima {

namespace {

// Points and normals of a patch, its mirror rays from `eye`, ends at distance `far`.
struct Patch {
  std::vector<vec3> points, normals, ends;
};

void add_point(Patch& patch, vec3 eye, vec3 p, vec3 n, float far) {
  patch.points.push_back(p);
  patch.normals.push_back(n);
  patch.ends.push_back(p + far * reflect(glm::normalize(p - eye), n));
}

ClusterCameraInput input(const Patch& patch, vec3 eye) {
  ClusterCameraInput in;
  in.points = patch.points;
  in.normals = patch.normals;
  in.ray_ends = patch.ends;
  in.eye = eye;
  in.pixel_footprint = 0.02f;
  in.plane_tolerance = 1e-4f;
  return in;
}

}  // namespace

// A cap of the unit sphere at the origin facing +Z, 11 × 11 points, seen from `eye`.
Patch unit_sphere_cap(vec3 eye) {
  Patch patch;
  for (int i = -5; i <= 5; ++i)
    for (int j = -5; j <= 5; ++j) {
      vec3 n = glm::normalize(vec3(0.06f * float(i), 0.06f * float(j), 1.0f));
      add_point(patch, eye, n, n, 20.0f);
    }
  return patch;
}

TEST(ClusterCamera, ConvexReflectorMovesCenterTowardsThePlane) {
  // A cap of a unit sphere at the origin, seen from +Z.
  const vec3 eye(0.3f, 0.4f, 4.0f);
  const Patch patch = unit_sphere_cap(eye);
  auto k = build_cluster_camera(input(patch, eye));
  ASSERT_TRUE(k.has_value());
  EXPECT_FALSE(k->planar);
  EXPECT_GT(k->f, 0.0f);
  EXPECT_LT(k->f, 1.0f);
  EXPECT_GT(k->d_f, k->d_n);
  // e_c lies on the segment e0 → P_c, strictly between them.
  const vec3 ec = k->camera.position;
  const float along = glm::dot(ec - k->mirrored_eye, glm::normalize(k->plane_point - k->mirrored_eye));
  EXPECT_GT(along, 0.0f);
  EXPECT_LT(along, glm::length(k->plane_point - k->mirrored_eye));
  EXPECT_NEAR(glm::length(glm::cross(ec - k->mirrored_eye, k->plane_point - k->mirrored_eye)), 0.0f, 1e-4f);
}

TEST(ClusterCamera, CurvedClusterNearPlaneKeepsEveryPoint) {
  // The same cap: its rim lies behind the fitting plane (through the mean point), the near
  // plane must not: every ray starts in front of it.
  const vec3 eye(0.3f, 0.4f, 4.0f);
  const Patch patch = unit_sphere_cap(eye);
  auto k = build_cluster_camera(input(patch, eye));
  ASSERT_TRUE(k.has_value());
  float lowest = kInf;
  for (vec3 p : patch.points) lowest = std::min(lowest, glm::dot(p - k->plane_point, k->plane_normal));
  EXPECT_LT(lowest, -0.01f);  // the rim is well behind the fitting plane
  EXPECT_LT(k->clip_offset, lowest);
  EXPECT_GT(k->clip_offset, lowest - 2e-4f);
}

TEST(ClusterCamera, PlanarClusterUsesTheMirroredEye) {
  const vec3 eye(0.5f, 1.6f, 3.0f);
  Patch patch;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) add_point(patch, eye, vec3(-1.0f + 0.1f * float(i), 0.0f, -1.0f + 0.1f * float(j)), vec3(0, 1, 0), 15.0f);
  ClusterCameraInput in = input(patch, eye);
  in.pixel_footprint = 0.1f;  // the points' spacing
  auto k = build_cluster_camera(in);
  ASSERT_TRUE(k.has_value());
  EXPECT_TRUE(k->planar);
  EXPECT_EQ(k->f, 1.0f);
  EXPECT_EQ(k->camera.position, k->mirrored_eye);
  EXPECT_GT(k->clip_offset, 0.0f);  // the fitting plane itself, clear of the mirror's surface
  EXPECT_NEAR(k->mirrored_eye.y, -1.6f, 1e-5f);
  // Every reflection ray passes through e0: its start and end project to the same pixel.
  for (size_t i = 0; i < patch.points.size(); i += 37) {
    auto a = project(k->camera, patch.points[i]);
    auto b = project(k->camera, patch.ends[i]);
    ASSERT_TRUE(a && b);
    EXPECT_NEAR(glm::length(a->pixel - b->pixel), 0.0f, 0.05f);
    EXPECT_GE(a->pixel.x, 0.0f);
    EXPECT_LE(a->pixel.x, float(k->camera.width));
  }
  // About one texel per pixel footprint over the 2.1 × 2.1 m window (with its margin)
  // inside an image that also covers the window's trapezoid hull.
  EXPECT_GT(k->camera.width * k->camera.height, 400);
  EXPECT_LT(k->camera.width * k->camera.height, 4 * 441);
}

TEST(ClusterCamera, EmptyClusterHasNoCamera) {
  ClusterCameraInput in;
  EXPECT_FALSE(build_cluster_camera(in).has_value());
}

}  // namespace proxima
