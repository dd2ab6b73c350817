// Distance cube maps: Euclidean distances against ray/box intersections, d_inf where
// nothing is hit, the reflector left out, seams between faces, determinism across threads.
#include "proxima/reflect/distance_cube_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/scene/procedural.h"
#include "reflect_test_scenes.h"

namespace proxima {
namespace {

using reflect_test::add_diffuse;
using reflect_test::add_quad;
using reflect_test::box_room;

// Distance from p along unit dir to the inside of the box [lo, hi] (p inside); `wall`
// receives the exit plane (0..5).
float box_exit(vec3 p, vec3 dir, vec3 lo, vec3 hi, int* wall = nullptr) {
  float t = kInf;
  for (int k = 0; k < 3; ++k) {
    float tk = dir[k] > 0.0f ? (hi[k] - p[k]) / dir[k] : dir[k] < 0.0f ? (lo[k] - p[k]) / dir[k] : kInf;
    if (tk < t) {
      t = tk;
      if (wall) *wall = 2 * k + (dir[k] > 0.0f);
    }
  }
  return t;
}

// True when every direction within `angle` of dir leaves the box through the same wall
// (no crease of the room under the bilinear footprint).
bool away_from_creases(vec3 p, vec3 dir, vec3 lo, vec3 hi, float angle) {
  int w0 = 0, w = 0;
  box_exit(p, dir, lo, hi, &w0);
  for (vec3 axis : {vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)}) {
    vec3 side = glm::cross(dir, axis);
    if (glm::length(side) < 1e-3f) continue;
    side = glm::normalize(side);
    for (float sgn : {-1.0f, 1.0f}) {
      box_exit(p, glm::normalize(dir + sgn * angle * side), lo, hi, &w);
      if (w != w0) return false;
    }
  }
  return true;
}

vec3 random_dir(Pcg32& rng) {
  for (;;) {
    vec3 d(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
    float l = glm::length(d);
    if (l > 0.1f && l <= 1.0f) return d / l;
  }
}

DistanceCubeMapOptions small(int resolution) {
  DistanceCubeMapOptions o;
  o.resolution = resolution;
  o.area_light_samples = 1;
  return o;
}

TEST(DistanceCubeMap, StoresEuclideanDistanceToTheCenter) {
  const vec3 lo(-2, -1, -3), hi(3, 2, 2), c(0.3f, -0.2f, 0.1f);
  Scene s = box_room(lo, hi);
  RayScene rays(s);
  DistanceCubeMap map = render_distance_cube_map(s, rays, c, small(96));
  EXPECT_DOUBLE_EQ(map.covered_fraction, 1.0);
  Pcg32 rng(7);
  int tested = 0;
  for (int i = 0; i < 2000; ++i) {
    vec3 d = random_dir(rng);
    // Across a crease the distance has a kink that bilinear filtering rounds off.
    if (!away_from_creases(c, d, lo, hi, 3.0f / 96.0f)) continue;
    ++tested;
    CubeSample smp = sample_cube(map, d);
    ASSERT_FALSE(smp.empty) << i;
    float want = box_exit(c, d, lo, hi);
    // Bilinear filtering of a smooth distance: well below a texel's worth (~3% here).
    EXPECT_NEAR(smp.distance, want, 4e-3f * want) << "dir " << d.x << " " << d.y << " " << d.z;
  }
  EXPECT_GT(tested, 1500);
}

TEST(DistanceCubeMap, EmptyDirectionsHoldDInf) {
  Scene s;
  uint32_t white = add_diffuse(s, vec3(0.8f));
  // A 2 × 2 m wall at x = 3 facing −X; nothing else.
  add_quad(s, {3, -1, -1}, {0, 0, 2}, {0, 2, 0}, white, "wall");
  s.point_lights.push_back({vec3(0.0f), vec3(1.0f)});
  RayScene rays(s);
  DistanceCubeMap map = render_distance_cube_map(s, rays, vec3(0.0f), small(32));
  CubeSample hit = sample_cube(map, {1, 0, 0});
  ASSERT_FALSE(hit.empty);
  // Bilinear between texel centers half a texel off axis: 3·√(1 + 2/32²) ≈ 3.003.
  EXPECT_NEAR(hit.distance, 3.0f, 5e-3f);
  EXPECT_EQ(hit.object, 0u);
  for (vec3 d : {vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, 0, -1), vec3(1, 1, 0)}) {
    CubeSample miss = sample_cube(map, d);
    EXPECT_TRUE(miss.empty);
    EXPECT_EQ(miss.distance, kDistanceInf);
  }
  // Only the +X face holds anything; the other faces stay unallocated.
  for (int f = 1; f < 6; ++f) EXPECT_TRUE(map.faces[size_t(f)].empty()) << f;
  EXPECT_NEAR(map.covered_fraction, 1.0 / 6.0 * (2.0 / 6.0) * (2.0 / 6.0) * 1.0, 0.01);
}

TEST(DistanceCubeMap, LeavesOutTheReflector) {
  const vec3 lo(-2, -2, -2), hi(2, 2, 2);
  Scene s = box_room(lo, hi);
  const uint32_t ball = add_object(s, make_sphere(0.5f, 24, 12), "ball", add_diffuse(s, vec3(0.9f), 1.0f));
  RayScene rays(s);
  const uint32_t exclude[] = {ball};
  DistanceCubeMapOptions o = small(32);
  o.exclude = exclude;
  DistanceCubeMap map = render_distance_cube_map(s, rays, vec3(0.0f), o);
  for (int f = 0; f < 6; ++f)
    for (uint32_t obj : map.objects[size_t(f)].data()) ASSERT_NE(obj, ball);
  EXPECT_NEAR(sample_cube(map, {0, 0, 1}).distance, 2.0f, 5e-3f);
  // Without the exclusion the sphere (r = 0.5) fills every direction.
  DistanceCubeMap with = render_distance_cube_map(s, rays, vec3(0.0f), small(32));
  EXPECT_NEAR(sample_cube(with, {0, 0, 1}).distance, 0.5f, 1e-2f);
}

TEST(DistanceCubeMap, FilteringIsContinuousAcrossFaceEdges) {
  const vec3 lo(-2, -1, -3), hi(3, 2, 2), c(0.3f, -0.2f, 0.1f);
  Scene s = box_room(lo, hi);
  RayScene rays(s);
  const int res = 16;
  DistanceCubeMap map = render_distance_cube_map(s, rays, c, small(res));
  // Directions just either side of the +X / +Z edge and of the +X / +Y / +Z corner: the
  // two faces must blend the same texels and agree.
  for (vec3 edge : {vec3(1, 0.3f, 1), vec3(1, -0.6f, 1), vec3(1, 1, 0.2f), vec3(1, 1, 1)}) {
    const vec3 a = edge + vec3(1e-4f, 0, 0),
               b = edge + vec3(0, 0, 1e-4f) + vec3(0, edge.y == 1 ? 1e-4f : 0, 0);
    CubeSample sa = sample_cube(map, a), sb = sample_cube(map, b);
    ASSERT_NE(cube_lookup(map.camera, a).face, cube_lookup(map.camera, b).face);
    EXPECT_NEAR(sa.distance, sb.distance, 2e-3f * sa.distance) << edge.x << " " << edge.y << " " << edge.z;
  }
  // The test could fail: a single face's edge texel differs from the filtered value by
  // much more than the tolerance (the distance changes by a few % per texel at res 16).
  CubeTexel t = cube_lookup(map.camera, vec3(1, 0.3f, 1) + vec3(1e-4f, 0, 0));
  const float edge_texel = map.faces[size_t(t.face)].at(res - 1, int(t.pixel.y), 3);
  EXPECT_GT(std::abs(edge_texel - sample_cube(map, vec3(1, 0.3f, 1)).distance), 1e-2f);
}

TEST(DistanceCubeMap, SameForAnyThreadCount) {
  Scene s = box_room({-2, -1, -3}, {3, 2, 2});
  AreaLight a;
  a.corner = {-0.5f, 1.9f, -0.5f};
  a.edge_u = {1, 0, 0};
  a.edge_v = {0, 0, 1};  // faces down
  s.area_lights.push_back(a);
  RayScene rays(s);
  DistanceCubeMapOptions o = small(40);
  o.area_light_samples = 2;
  DistanceCubeMap one, two;
  {
    ThreadLimit limit(1);
    one = render_distance_cube_map(s, rays, vec3(0.1f), o);
  }
  {
    ThreadLimit limit(2);
    two = render_distance_cube_map(s, rays, vec3(0.1f), o);
  }
  for (int f = 0; f < 6; ++f) {
    EXPECT_TRUE(one.faces[size_t(f)] == two.faces[size_t(f)]) << f;
    EXPECT_TRUE(one.objects[size_t(f)] == two.objects[size_t(f)]) << f;
  }
}

TEST(DistanceCubeMap, DistanceOnlyLookupMatchesTheFullOne) {
  // A wall with a card in front of it, crossing the +X/+Z edge: silhouettes, seams, empties.
  Scene s;
  const uint32_t white = add_diffuse(s, vec3(0.8f));
  add_quad(s, {2, -2, -1}, {0, 0, 4}, {0, 4, 0}, white, "wall");
  add_quad(s, {1, -0.3f, 0.6f}, {0, 0, 0.8f}, {0, 0.6f, 0}, white, "card");
  s.ambient = vec3(1.0f);
  RayScene rays(s);
  DistanceCubeMap map = render_distance_cube_map(s, rays, vec3(0.0f), small(24));
  Pcg32 rng(2);
  int empty = 0, full_hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const vec3 d = random_dir(rng);
    const CubeSample full = sample_cube(map, d);
    const float fast = sample_distance(map, d);
    if (full.empty) {
      EXPECT_EQ(fast, kDistanceInf);
      ++empty;
    } else {
      EXPECT_NEAR(fast, full.distance, 1e-5f * full.distance);
      ++full_hits;
    }
  }
  EXPECT_GT(empty, 1000);
  EXPECT_GT(full_hits, 300);
  // Degenerate directions are empty, never undefined.
  EXPECT_TRUE(sample_cube(map, vec3(0.0f)).empty);
  EXPECT_EQ(sample_distance(map, vec3(0.0f)), kDistanceInf);
  EXPECT_TRUE(sample_cube(map, vec3(std::nanf(""), 0.0f, 0.0f)).empty);
}

TEST(DistanceCubeMap, RejectsBadResolution) {
  Scene s = box_room({-1, -1, -1}, {1, 1, 1});
  RayScene rays(s);
  EXPECT_THROW(render_distance_cube_map(s, rays, vec3(0.0f), small(0)), InputError);
}

}  // namespace
}  // namespace proxima
