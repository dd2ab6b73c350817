// Env-map lookups with position rectification (§2.2–2.3): far environments, a planar
// mirror facing a planar wall (analytic hit), the step bound N, the d_inf edge rule, the
// average distance; and the layered (depth-peeled) lookup against Embree's rays.
#include "proxima/reflect/envmap_lookup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/rng.h"
#include "proxima/trace/ray_scene.h"
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

// A room with a panel between c and the +Z wall and a small card right behind the panel:
// from c the card is hidden (it is in no texel of the ordinary distance map), from points
// 1.2 m to the side of c the rays pass beside the panel and meet it.
struct HiddenBoxScene {
  Scene scene;
  uint32_t panel = 0, box = 0;
  vec3 box_color{0.9f, 0.9f, 0.1f};

  HiddenBoxScene() : scene(box_room({-4, -4, -4}, {4, 4, 4})) {
    Mesh p = make_box(vec3(0.8f, 0.8f, 0.04f), 1);
    transform_mesh(p, glm::translate(mat4(1.0f), vec3(0, 0, 1.5f)));
    panel = add_object(scene, p, "panel", add_diffuse(scene, vec3(0.1f, 0.1f, 0.9f)));
    // A card facing c: a box's sides would be seen edge-on from c, in no layer (gap).
    box = add_quad(scene, {0.2f, -0.2f, 3.5f}, {-0.4f, 0, 0}, {0, 0.4f, 0}, add_diffuse(scene, box_color), "card");
    scene.ambient = vec3(1.0f);
    scene.point_lights.clear();  // texel radiance = albedo: colors compare exactly
  }
};

TEST(EnvmapLookup, LayeredFindsASurfaceHiddenFromTheCentreAsEmbreeDoes) {
  HiddenBoxScene h;
  RayScene rays(h.scene);
  DistanceCubeLayerOptions lo;
  lo.layers = 3;
  lo.viewer_radius = 1.3f;
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(h.scene, rays, vec3(0.0f), small(128), lo);
  ASSERT_GE(layers.size(), 2u);
  // The box is in no texel of layer 0 (the ordinary map): no single-map method can show it.
  for (const ImageU32& face : layers[0].objects)
    for (uint32_t o : face.data()) ASSERT_NE(o, h.box);
  RectifyOptions o;
  o.D = 14.0f;
  int box_rays = 0, layered_right = 0, rectified_right = 0;
  for (float side : {-1.2f, 1.2f})
    for (float y : {-0.1f, 0.0f, 0.1f})
      for (float bx : {-0.1f, 0.0f, 0.1f}) {
        const vec3 x(side, y, 0.0f);
        const vec3 dir = glm::normalize(vec3(bx, 0.05f, 3.5f) - x);
        const Hit hit = rays.intersect(Ray{x, dir, 0.0f, kInf});
        ASSERT_TRUE(hit.valid());
        if (h.scene.triangle_object[hit.triangle] != h.box) continue;  // the ray meets the panel
        ++box_rays;
        const EnvLookup l = layered_lookup(layers, h.scene.environment, x, dir, o);
        const EnvLookup r = rectified_lookup(layers[0], h.scene.environment, x, dir, o);
        EXPECT_GE(l.layer, 1) << x.x << " " << x.y << " " << bx << " obj " << l.object << " fb " << l.fallback << " steps " << l.steps << " t " << hit.t << " q " << l.query.x << "," << l.query.y << "," << l.query.z;
        layered_right += l.object == h.box;
        rectified_right += r.object == h.box;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(l.color[c], h.box_color[c], 1e-3f);
        // The hit point: on the ray within d_e of Embree's.
        EXPECT_LE(glm::length(l.query - (x + hit.t * dir)), 2.0f * o.d_e);
      }
  EXPECT_GE(box_rays, 6);
  EXPECT_EQ(layered_right, box_rays);
  EXPECT_EQ(rectified_right, 0);
}

TEST(EnvmapLookup, LayeredAgreesWithEmbreeOnRandomRaysWhereRectifiedFails) {
  // Random rays from points within 1.2 m of c: the object the layered lookup returns is
  // Embree's (except within a texel of a silhouette), more often than the rectified one.
  HiddenBoxScene h;
  RayScene rays(h.scene);
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = 1.3f;
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(h.scene, rays, vec3(0.0f), small(256), lo);
  RectifyOptions o;
  o.D = 14.0f;
  Pcg32 rng(17);
  int total = 0, layered_ok = 0, rectified_ok = 0;
  for (int i = 0; i < 4000; ++i) {
    const vec3 x = 1.2f * random_dir(rng) * std::sqrt(rng.next_float());
    vec3 dir = random_dir(rng);
    if (dir.z < 0.5f) dir.z = -dir.z + 0.5f;  // mostly towards the panel and the box
    dir = glm::normalize(dir);
    const Hit hit = rays.intersect(Ray{x, dir, 0.0f, kInf});
    if (!hit.valid()) continue;
    ++total;
    const uint32_t want = h.scene.triangle_object[hit.triangle];
    layered_ok += layered_lookup(layers, h.scene.environment, x, dir, o).object == want;
    rectified_ok += rectified_lookup(layers[0], h.scene.environment, x, dir, o).object == want;
  }
  ASSERT_GT(total, 3000);
  EXPECT_GE(layered_ok, total * 99 / 100) << layered_ok << " of " << total;
  EXPECT_GT(layered_ok, rectified_ok) << rectified_ok << " of " << total;
}

TEST(EnvmapLookup, LayeredHitsASeamBetweenTwoObjectsSeenAtAGrazingAngle) {
  // A floor of two quads (two objects) meeting at z = −3, 1 m below c, seen from c at 18°
  // below the horizon: at 128² neighbouring texels across the seam differ by ~4% in
  // distance, more than a silhouette's threshold, yet the floor is one plane. A basement
  // below it fills layer 1. Every ray Embree sends to the floor near the seam must show
  // the floor, not the basement behind it (nor the surroundings of a silhouette).
  Scene s;
  const vec3 floor_color(0.6f, 0.5f, 0.4f);
  const uint32_t fm = add_diffuse(s, floor_color);
  const uint32_t far = add_quad(s, {-3, -1, -6}, {0, 0, 3}, {6, 0, 0}, fm, "floor_far");
  const uint32_t near = add_quad(s, {-3, -1, -3}, {0, 0, 3}, {6, 0, 0}, fm, "floor_near");
  add_quad(s, {-3, -1.6f, -6}, {0, 0, 6}, {6, 0, 0}, add_diffuse(s, vec3(0.1f, 0.9f, 0.1f)), "basement");
  s.ambient = vec3(1.0f);  // no lights: texel radiance = albedo
  s.environment.color = {0.1f, 0.2f, 0.9f};
  RayScene rays(s);
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = 0.3f;
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(s, rays, vec3(0.0f), small(128), lo);
  ASSERT_GE(layers.size(), 2u);
  RectifyOptions o;
  o.D = 10.0f;
  int floor_rays = 0, layered_right = 0;
  for (float xx : {-0.2f, 0.0f, 0.2f})
    for (float px = -1.0f; px <= 1.0f; px += 0.25f)
      for (float jz = -0.06f; jz <= 0.061f; jz += 0.01f) {
        const vec3 x(xx, 0.1f, 0.1f);
        const vec3 dir = glm::normalize(vec3(px, -1.0f, -3.0f + jz) - x);
        const Hit hit = rays.intersect(Ray{x, dir, 0.0f, kInf});
        ASSERT_TRUE(hit.valid());
        const uint32_t want = s.triangle_object[hit.triangle];
        ASSERT_TRUE(want == far || want == near);
        ++floor_rays;
        const EnvLookup l = layered_lookup(layers, s.environment, x, dir, o);
        const bool right = (l.object == far || l.object == near) && glm::length(l.color - floor_color) < 1e-3f;
        layered_right += right;
        EXPECT_TRUE(right) << "x " << xx << " to (" << px << ", −1, " << -3.0f + jz << "): object " << l.object
                           << " layer " << l.layer << " fallback " << l.fallback;
      }
  EXPECT_EQ(floor_rays, 3 * 9 * 13);
  EXPECT_EQ(layered_right, floor_rays);
}

TEST(EnvmapLookup, LayeredWithOneLayerNeverLooksBehindIt) {
  HiddenBoxScene h;
  RayScene rays(h.scene);
  DistanceCubeLayerOptions lo;
  lo.layers = 1;
  lo.viewer_radius = 1.3f;
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(h.scene, rays, vec3(0.0f), small(64), lo);
  ASSERT_EQ(layers.size(), 1u);
  const vec3 x(1.2f, 0.0f, 0.0f);
  const vec3 dir = glm::normalize(vec3(0, 0.05f, 3.5f) - x);
  const EnvLookup l = layered_lookup(layers, h.scene.environment, x, dir, RectifyOptions{});
  EXPECT_NE(l.object, h.box);
  EXPECT_EQ(l.layer, 0);
}

TEST(EnvmapLookup, LayeredEscapesToTheEnvironmentWhereNothingIsHit) {
  // One wall: rays beside it see the environment (not black), rays at it see the wall.
  Scene s;
  const vec3 wall_color(0.7f, 0.6f, 0.5f);
  add_quad(s, {-2, -2, -3}, {4, 0, 0}, {0, 4, 0}, add_diffuse(s, wall_color), "wall");
  s.ambient = vec3(1.0f);
  s.environment.color = {0.1f, 0.2f, 0.9f};
  RayScene rays(s);
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = 0.3f;
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(s, rays, vec3(0.0f), small(128), lo);
  RectifyOptions o;
  Pcg32 rng(9);
  int hits = 0, escapes = 0;
  for (int i = 0; i < 2000; ++i) {
    const vec3 x = 0.3f * (vec3(rng.next_float(), rng.next_float(), 0.0f) - 0.5f);
    const vec3 l = glm::normalize(vec3(2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f, -1.0f));
    const vec3 p = x + (-3.0f - x.z) / l.z * l;
    const float inside = 2.0f - std::max(std::abs(p.x), std::abs(p.y));
    if (std::abs(inside) < 0.05f) continue;  // within about a texel of the wall's edge
    const EnvLookup r = layered_lookup(layers, s.environment, x, l, o);
    if (inside > 0.0f) {
      ++hits;
      EXPECT_FALSE(r.miss) << i << " inside " << inside << " p " << p.x << "," << p.y << " fb " << r.fallback << " steps " << r.steps << " x " << x.x << "," << x.y << " l " << l.x << "," << l.y << "," << l.z;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.color[c], wall_color[c], 1e-3f) << i;
    } else {
      ++escapes;
      EXPECT_TRUE(r.miss) << i;
      EXPECT_EQ(r.color, s.environment.color) << i;
    }
  }
  EXPECT_GT(hits, 300);
  EXPECT_GT(escapes, 300);
}

}  // namespace
}  // namespace proxima
