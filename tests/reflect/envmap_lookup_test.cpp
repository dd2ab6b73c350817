// Env-map lookups with position rectification (§2.2–2.4): far environments, a planar
// mirror facing a planar wall (analytic hit), the step bound N, the d_inf edge rule, the
// average distance, and layers.
#include "proxima/reflect/envmap_lookup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/rng.h"
#include "proxima/scene/procedural.h"
#include "reflect_test_scenes.h"

namespace proxima {
namespace {

using reflect_test::add_diffuse;
using reflect_test::add_quad;
using reflect_test::box_room;

DistanceCubeMapOptions small(int resolution) {
  DistanceCubeMapOptions o;
  o.resolution = resolution;
  o.area_light_samples = 1;
  return o;
}

// Unit direction with components uniform in [−1, 1], rejecting short ones.
vec3 random_dir(Pcg32& rng) {
  for (;;) {
    vec3 d(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
    float l = glm::length(d);
    if (l > 0.1f && l <= 1.0f) return d / l;
  }
}

TEST(EnvmapLookup, StepLimitIsLog2Of2DOverDe) {
  EXPECT_EQ(rectify_step_limit(12.0f, 0.01f), 12);  // log2(2400) = 11.23
  EXPECT_EQ(rectify_step_limit(12.0f, 0.1f), 8);    // log2(240) = 7.91
  EXPECT_EQ(rectify_step_limit(8.0f, 1.0f), 4);     // exactly 2^4
  EXPECT_EQ(rectify_step_limit(1.0f, 10.0f), 1);
}

TEST(EnvmapLookup, FarEnvironmentRectifiedEqualsPlainWithinATexel) {
  // Walls 500 m away, reflector points within 0.5 m of c: distance ratio ≥ 1000.
  const vec3 lo(-500, -500, -500), hi(500, 500, 500);
  Scene s = box_room(lo, hi);
  RayScene rays(s);
  const int res = 64;
  DistanceCubeMap map = render_distance_cube_map(s, rays, vec3(0.0f), small(res));
  RectifyOptions o;
  o.D = glm::length(hi - lo);
  o.d_e = 0.5f;
  Pcg32 rng(3);
  for (int i = 0; i < 500; ++i) {
    const vec3 x = 0.5f * (vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f);
    const vec3 dir = random_dir(rng);
    EnvLookup rect = rectified_lookup(map, s.environment, x, dir, o);
    EnvLookup plain = plain_lookup(map, s.environment, dir);
    ASSERT_TRUE(rect.converged) << i;
    const CubeTexel a = cube_lookup(map.camera, rect.query), b = cube_lookup(map.camera, dir);
    if (a.face != b.face) continue;  // on an edge: both sides are the same texels (seam test)
    EXPECT_LE(glm::length(a.pixel - b.pixel), 1.0f) << i;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rect.color[c], plain.color[c], 0.05f) << i;
  }
}

TEST(EnvmapLookup, PlanarMirrorFindsTheAnalyticWallPoint) {
  // Mirror plane z = 0 around c = 0; a textured-free wall at z = −3 facing it.
  Scene s;
  add_quad(s, {-10, -10, -3}, {20, 0, 0}, {0, 20, 0}, add_diffuse(s, vec3(0.7f)), "wall");
  s.point_lights.push_back({vec3(0, 0, 1), vec3(5.0f)});
  RayScene rays(s);
  DistanceCubeMap map = render_distance_cube_map(s, rays, vec3(0.0f), small(256));
  RectifyOptions o;  // the paper's D = 12, d_e = 0.01
  const int N = rectify_step_limit(o.D, o.d_e);
  Pcg32 rng(11);
  int converged = 0;
  for (int i = 0; i < 400; ++i) {
    const vec3 x(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 0.0f);
    // A view ray hitting the mirror, reflected about its normal +Z.
    const vec3 view = glm::normalize(vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 1.0f));
    const vec3 l = glm::normalize(view - 2.0f * view.z * vec3(0, 0, 1));
    const vec3 p = x + (-3.0f - x.z) / l.z * l;
    EnvLookup r = rectified_lookup(map, s.environment, x, l, o);
    EXPECT_LE(r.steps, N);
    EXPECT_FALSE(r.miss);
    converged += r.converged;
    // The color comes from the wall point seen from c through l1: within d_e of p. The
    // query point itself is within d_e of the wall radially (condition 1), which along
    // the ray can be a little more.
    const vec3 seen = (-3.0f / (r.query.z)) * r.query;
    EXPECT_LE(glm::length(seen - p), o.d_e) << i;
    EXPECT_LE(glm::length(r.query - p), 1.5f * o.d_e) << i;
    // Plain mapping looks along l from c and lands elsewhere on the wall.
    const vec3 plain_point = (-3.0f / l.z) * l;
    if (glm::length(vec2(x)) > 0.2f) {
      EXPECT_GT(glm::length(plain_point - p), 0.1f);
    }
  }
  EXPECT_EQ(converged, 400);
}

TEST(EnvmapLookup, BisectionEndsWithinNSteps) {
  const vec3 lo(-4, 0, -4), hi(4, 4, 4);
  Scene s = box_room(lo, hi);
  RayScene rays(s);
  const vec3 c(0, 1, 0);
  DistanceCubeMap map = render_distance_cube_map(s, rays, c, small(128));
  for (float d_e : {0.1f, 0.01f}) {
    RectifyOptions o;
    o.d_e = d_e;
    const int N = rectify_step_limit(o.D, o.d_e);
    Pcg32 rng(5);
    int converged = 0, total = 1000, max_steps = 0;
    for (int i = 0; i < total; ++i) {
      const vec3 x = c + 0.5f * random_dir(rng);
      EnvLookup r = rectified_lookup(map, s.environment, x, random_dir(rng), o);
      max_steps = std::max(max_steps, r.steps);
      converged += r.converged;
      EXPECT_FALSE(r.saw_inf);  // a closed room: no empty texels
    }
    EXPECT_LE(max_steps, N) << d_e;
    EXPECT_GE(converged, total * 99 / 100) << d_e;
  }
}

TEST(EnvmapLookup, DInfGivesBlackOrFallbackOnlyWhereTheRayEscapes) {
  // One 4 × 4 m wall at z = −3 facing +Z; the environment beyond is blue.
  Scene s;
  const vec3 wall_color(0.7f, 0.6f, 0.5f);
  add_quad(s, {-2, -2, -3}, {4, 0, 0}, {0, 4, 0}, add_diffuse(s, wall_color), "wall");
  s.ambient = vec3(1.0f);  // the wall's radiance is exactly its albedo
  s.environment.color = {0.1f, 0.2f, 0.9f};
  RayScene rays(s);
  DistanceCubeMap map = render_distance_cube_map(s, rays, vec3(0.0f), small(128));
  RectifyOptions black, fallback;
  fallback.edge = EdgeRule::PlainFallback;
  Pcg32 rng(9);
  int hits = 0, escapes = 0;
  for (int i = 0; i < 3000; ++i) {
    const vec3 x = 0.3f * (vec3(rng.next_float(), rng.next_float(), 0.0f) - 0.5f);
    const vec3 l =
        glm::normalize(vec3(2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f, -1.0f));
    const vec3 p = x + (-3.0f - x.z) / l.z * l;
    const float inside = 2.0f - std::max(std::abs(p.x), std::abs(p.y));  // > 0: hits the wall
    // Near the wall's edge the search may look past it from c (the sign condition of §2.2
    // fails within about |x − c| of the edge): either answer is allowed there.
    if (std::abs(inside) < glm::length(x) + 0.05f) continue;
    EnvLookup b = rectified_lookup(map, s.environment, x, l, black);
    EnvLookup f = rectified_lookup(map, s.environment, x, l, fallback);
    if (inside > 0.0f) {
      ++hits;
      EXPECT_FALSE(b.miss) << i;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.color[c], wall_color[c], 1e-3f) << i;
      EXPECT_EQ(b.color, f.color);
    } else {
      ++escapes;
      EXPECT_TRUE(b.miss) << i;
      EXPECT_EQ(b.color, vec3(0.0f)) << i;
      EXPECT_TRUE(f.miss);
      // The fallback is the plain lookup along l: the environment unless l sees the wall from c.
      EXPECT_EQ(f.color, plain_lookup(map, s.environment, l).color);
    }
  }
  EXPECT_GT(hits, 300);
  EXPECT_GT(escapes, 300);
}

TEST(EnvmapLookup, AverageDistanceOfACenteredSphereIsItsRadius) {
  Scene s;
  add_object(s, make_sphere(1.5f, 64, 32), "ball", add_diffuse(s, vec3(0.5f)));
  s.ambient = vec3(1.0f);
  RayScene rays(s);
  DistanceCubeMap map = render_distance_cube_map(s, rays, vec3(0.0f), small(64));
  // The tessellated sphere's surface lies between 1.5·cos(π/64)… and 1.5.
  EXPECT_NEAR(average_distance(map, glm::radians(5.0f)), 1.5f, 0.01f);
  // Off center, eq. 3 averages over directions: between the nearest and farthest point.
  DistanceCubeMap off = render_distance_cube_map(s, rays, vec3(0.5f, 0, 0), small(64));
  const float d = average_distance(off, glm::radians(5.0f));
  EXPECT_GT(d, 1.0f);
  EXPECT_LT(d, 2.0f);
  EXPECT_GT(std::abs(d - 1.5f), 0.01f);
}

TEST(EnvmapLookup, LayersResolveOcclusionNearToFar) {
  // A room with a small box between c and the +Z wall: the box is a layer of its own,
  // the six walls (all facing c) form the enclosure layer behind it.
  Scene s = box_room({-4, -4, -4}, {4, 4, 4});
  Mesh cube = make_box(vec3(0.6f), 1);
  transform_mesh(cube, glm::translate(mat4(1.0f), vec3(0, 0, 2)));
  const uint32_t box = add_object(s, cube, "box", add_diffuse(s, vec3(0.9f, 0.9f, 0.1f)));
  RayScene rays(s);
  LayerOptions lo;
  lo.map = small(64);
  std::vector<EnvmapLayer> layers = build_layers(s, rays, vec3(0.0f), {}, lo);
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_EQ(layers[0].objects, std::vector<uint32_t>{box});
  EXPECT_FALSE(layers[0].per_pixel);  // 0.6 m at 2 m: a small solid angle → d̄
  EXPECT_EQ(layers[1].objects.size(), 6u);
  EXPECT_TRUE(layers[1].per_pixel);
  EXPECT_LT(layers[0].average_distance, layers[1].average_distance);

  RectifyOptions o;
  const vec3 x(0.2f, 0.0f, 0.0f);
  EXPECT_EQ(layered_lookup(layers, s.environment, x, {0, 0, 1}, o).object, box);
  // Past the box: the enclosure's walls, found by bisection in the second layer.
  EXPECT_EQ(layered_lookup(layers, s.environment, x, {0, 1.2f, 1}, o).object, 3u);  // ceiling
  EXPECT_EQ(layered_lookup(layers, s.environment, x, {0, 0.7f, 1}, o).object, 5u);  // wall_pz
  EXPECT_EQ(layered_lookup(layers, s.environment, x, {1, 0, 0}, o).object, 1u);     // wall_px
  EXPECT_FALSE(layers[0].enclosure);
  EXPECT_TRUE(layers[1].enclosure);
  // Excluding the box leaves the enclosure only.
  const uint32_t exclude[] = {box};
  EXPECT_EQ(build_layers(s, rays, vec3(0.0f), exclude, lo).size(), 1u);
}

TEST(EnvmapLookup, TheEnclosureIsTheLastLayerEvenWhenNearerOnAverage) {
  // c half a meter above the floor: the room's d̄ is small, a box by the far wall is
  // farther on average, yet it stands inside the room and must be looked up first.
  Scene s = box_room({-4, -0.5f, -4}, {4, 4, 4});
  Mesh cube = make_box(vec3(0.6f), 1);
  transform_mesh(cube, glm::translate(mat4(1.0f), vec3(0, 0, 3.6f)));
  const uint32_t box = add_object(s, cube, "box", add_diffuse(s, vec3(0.9f, 0.9f, 0.1f)));
  RayScene rays(s);
  LayerOptions lo;
  lo.map = small(64);
  std::vector<EnvmapLayer> layers = build_layers(s, rays, vec3(0.0f), {}, lo);
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_GT(layers[0].average_distance, layers[1].average_distance);
  EXPECT_EQ(layers[0].objects, std::vector<uint32_t>{box});
  EXPECT_TRUE(layers[1].enclosure);
  EXPECT_EQ(layered_lookup(layers, s.environment, vec3(0.1f, 0, 0), {0, 0, 1}, RectifyOptions{}).object, box);
}

}  // namespace
}  // namespace proxima
