#include "proxima/trace/ray_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "proxima/core/rng.h"
#include "trace/test_geometry.h"

namespace proxima {
namespace {

using test::quad_mesh;
using test::sphere_mesh;

// Square [−1, 1]² in the plane z = z0, facing +Z.
Scene plane_scene(float z0) {
  Scene s;
  uint32_t mat = test::add_diffuse(s, vec3(0.5f));
  add_object(s, quad_mesh(vec3(-1, -1, z0), vec3(2, 0, 0), vec3(0, 2, 0)), "plane", mat);
  return s;
}

vec3 unit_dir(Pcg32& rng) {
  float z = 2.0f * rng.next_float() - 1.0f;
  float phi = 2.0f * kPi * rng.next_float();
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return vec3(r * std::cos(phi), r * std::sin(phi), z);
}

TEST(RayScene, SphereHitsMatchAnalyticWithinTessellationError) {
  const vec3 center(0.3f, -0.2f, 0.1f);
  const float radius = 1.5f;
  const int segments = 256, rings = 128;
  Scene s;
  add_object(s, sphere_mesh(center, radius, segments, rings), "sphere", test::add_diffuse(s, vec3(1)));
  RayScene rays(s);
  // Every facet's vertices lie on the sphere and its circumcircle spans at most Δ, so the
  // surface lies between radius·cos Δ and radius from the center.
  float delta = std::max(2.0f * kPi / segments, kPi / rings);
  float max_sag = radius * (1.0f - std::cos(delta));
  Pcg32 rng(1);
  for (int i = 0; i < 2000; ++i) {
    vec3 out = unit_dir(rng);
    float d = 2.0f + 4.0f * rng.next_float();
    Ray ray{center + d * out, -out, 0.0f, kInf};  // aimed at the center
    Hit hit = rays.intersect(ray);
    ASSERT_TRUE(hit.valid());
    EXPECT_GE(hit.t, d - radius - 1e-5f);
    EXPECT_LE(hit.t, d - radius + max_sag + 1e-5f);
    // The reported barycentrics reproduce the hit point.
    vec3 p = triangle_point(s, hit.triangle, hit.u, hit.v);
    EXPECT_NEAR(glm::distance(p, ray.origin + hit.t * ray.dir), 0.0f, 1e-4f);
    // Pointing away, or passing outside, misses.
    EXPECT_FALSE(rays.intersect(Ray{ray.origin, out, 0.0f, kInf}).valid());
    vec3 side = glm::normalize(glm::cross(out, unit_dir(rng)));
    EXPECT_FALSE(rays.intersect(Ray{center + 1.01f * radius * side + d * out, -out, 0.0f, kInf}).valid());
  }
}

TEST(RayScene, PlaneHitsAreExact) {
  Scene s = plane_scene(-2.0f);
  RayScene rays(s);
  Pcg32 rng(2);
  for (int i = 0; i < 1000; ++i) {
    vec3 target(1.8f * rng.next_float() - 0.9f, 1.8f * rng.next_float() - 0.9f, -2.0f);
    vec3 origin(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 1.0f + rng.next_float());
    vec3 dir = target - origin;  // not normalized: t = 1 at the plane
    Hit hit = rays.intersect(Ray{origin, dir, 0.0f, kInf});
    ASSERT_TRUE(hit.valid());
    EXPECT_NEAR(hit.t, 1.0f, 2e-6f);
    EXPECT_LT(hit.triangle, 2u);
    vec3 p = triangle_point(s, hit.triangle, hit.u, hit.v);
    EXPECT_NEAR(p.x, target.x, 2e-6f);
    EXPECT_NEAR(p.y, target.y, 2e-6f);
  }
  // Outside the square, or behind tmin / beyond tmax: no hit.
  EXPECT_FALSE(rays.intersect(Ray{vec3(1.5f, 0, 0), vec3(0, 0, -1), 0.0f, kInf}).valid());
  EXPECT_FALSE(rays.intersect(Ray{vec3(0, 0, 0), vec3(0, 0, -1), 2.5f, kInf}).valid());
  EXPECT_FALSE(rays.intersect(Ray{vec3(0, 0, 0), vec3(0, 0, -1), 0.0f, 1.9f}).valid());
  EXPECT_TRUE(rays.intersect(Ray{vec3(0, 0, 0), vec3(0, 0, -1), 0.0f, 2.1f}).valid());
  // Both sides are hit.
  EXPECT_NEAR(rays.intersect(Ray{vec3(0.2f, 0.1f, -5), vec3(0, 0, 1), 0.0f, kInf}).t, 3.0f, 1e-6f);
}

TEST(RayScene, TriangleIdIsTheGlobalSceneIndex) {
  Scene s = plane_scene(-2.0f);  // triangles 0, 1
  add_object(s, quad_mesh(vec3(-1, -1, -1), vec3(0.5f, 0, 0), vec3(0, 0.5f, 0)), "small", 0);  // 2, 3
  RayScene rays(s);
  Hit hit = rays.intersect(Ray{vec3(-0.6f, -0.9f, 0), vec3(0, 0, -1), 0.0f, kInf});
  ASSERT_TRUE(hit.valid());
  EXPECT_EQ(hit.triangle, 2u);  // lower-right half of the small quad
  EXPECT_NEAR(hit.t, 1.0f, 1e-6f);
  EXPECT_EQ(s.triangle_object[hit.triangle], 1u);
}

TEST(RayScene, Occlusion) {
  RayScene rays(plane_scene(-2.0f));
  EXPECT_TRUE(rays.occluded(Ray{vec3(0, 0, 0), vec3(0, 0, -4), 0.0f, 1.0f}));
  EXPECT_FALSE(rays.occluded(Ray{vec3(0, 0, 0), vec3(0, 0, -4), 0.0f, 0.49f}));
  EXPECT_FALSE(rays.occluded(Ray{vec3(0, 0, 0), vec3(0, 0, 1), 0.0f, kInf}));
  EXPECT_FALSE(rays.occluded(Ray{vec3(3, 0, 0), vec3(0, 0, -1), 0.0f, kInf}));
}

TEST(RayScene, EmptySceneHitsNothing) {
  Scene s;
  RayScene rays(s);
  EXPECT_FALSE(rays.intersect(Ray{}).valid());
  EXPECT_FALSE(rays.occluded(Ray{}));
  rays.update(s);
  EXPECT_FALSE(rays.intersect(Ray{}).valid());
}

TEST(RayScene, RefitAfterPoseMovesTheHit) {
  Scene s = plane_scene(-2.0f);
  RayScene rays(s);
  EXPECT_GE(rays.build_ms(), 0.0);
  const Ray down{vec3(0.3f, 0.2f, 0.0f), vec3(0, 0, -1), 0.0f, kInf};
  EXPECT_NEAR(rays.intersect(down).t, 2.0f, 1e-6f);
  for (float z : {-1.0f, -3.5f, -2.0f}) {
    Scene posed = s;
    for (vec3& p : posed.positions) p.z = z;
    rays.update(posed);
    EXPECT_NEAR(rays.intersect(down).t, -z, 1e-6f) << z;
    EXPECT_GE(rays.build_ms(), 0.0);
  }
  // Moving sideways out of the ray's path makes it miss.
  Scene moved = s;
  for (vec3& p : moved.positions) p.x += 5.0f;
  rays.update(moved);
  EXPECT_FALSE(rays.intersect(down).valid());
}

TEST(RayScene, BatchedQueriesEqualSingleOnes) {
  Scene s = plane_scene(-2.0f);
  add_object(s, sphere_mesh(vec3(0, 0, -1), 0.5f, 64, 32), "sphere", 0);
  RayScene rays(s);
  Pcg32 rng(9);
  std::vector<Ray> batch(5000);
  for (Ray& r : batch) {
    r.origin = vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 1.0f);
    // Half aimed into the scene, half anywhere.
    vec3 target(2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f, -2.0f * rng.next_float());
    r.dir = rng.next_float() < 0.5f ? target - r.origin : unit_dir(rng);
    r.tmax = rng.next_float() < 0.5f ? kInf : 3.0f * rng.next_float();
  }
  std::vector<Hit> hits(batch.size());
  std::vector<uint8_t> blocked(batch.size());
  rays.intersect(batch, hits);
  rays.occluded(batch, blocked);
  int hit_count = 0;
  for (size_t i = 0; i < batch.size(); ++i) {
    Hit single = rays.intersect(batch[i]);
    ASSERT_EQ(hits[i].triangle, single.triangle) << i;
    ASSERT_EQ(hits[i].t, single.t) << i;
    ASSERT_EQ(hits[i].u, single.u) << i;
    ASSERT_EQ(hits[i].v, single.v) << i;
    ASSERT_EQ(blocked[i] != 0, rays.occluded(batch[i])) << i;
    ASSERT_EQ(blocked[i] != 0, single.valid()) << i;
    hit_count += single.valid();
  }
  // Both outcomes are exercised.
  EXPECT_GT(hit_count, 500);
  EXPECT_LT(hit_count, 4500);
}

}  // namespace
}  // namespace proxima
