// Distance cube maps: Euclidean distances against ray/box intersections, d_inf where
// nothing is hit, the reflector left out, seams between faces, determinism across threads;
// layered maps: peeling order, back-face culling, reachable texels, the layer bound.
#include "proxima/reflect/distance_cube_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

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

// A room, a closed box (side `size`) in front of the +Z wall, its front face 1.5 m from c.
Scene room_with_box(uint32_t* box, float size = 1.0f) {
  Scene s = box_room({-4, -4, -4}, {4, 4, 4});
  Mesh b = make_box(vec3(size), 1);
  transform_mesh(b, glm::translate(mat4(1.0f), vec3(0, 0, 1.5f + 0.5f * size)));
  *box = add_object(s, b, "box", add_diffuse(s, vec3(0.9f, 0.9f, 0.1f)));
  return s;
}

TEST(DistanceCubeLayers, LayerZeroIsTheSingleMap) {
  uint32_t box = 0;
  Scene s = room_with_box(&box);
  RayScene rays(s);
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = 0.5f;
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(s, rays, vec3(0.0f), small(48), lo);
  const DistanceCubeMap single = render_distance_cube_map(s, rays, vec3(0.0f), small(48));
  ASSERT_GE(layers.size(), 2u);
  for (int f = 0; f < 6; ++f) {
    EXPECT_TRUE(layers[0].faces[size_t(f)] == single.faces[size_t(f)]) << f;
    EXPECT_TRUE(layers[0].objects[size_t(f)] == single.objects[size_t(f)]) << f;
  }
  EXPECT_EQ(layers[0].hidden_texels, 0u);
}

TEST(DistanceCubeLayers, PeelsTheNextFrontFacingSurfaceBehindEachTexel) {
  uint32_t box = 0;
  Scene s = room_with_box(&box);
  RayScene rays(s);
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = 0.4f;  // the box's sides (0.5 m from c) have the sphere behind them
  lo.reachable_only = false;
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(s, rays, vec3(0.0f), small(64), lo);
  // Behind the box's front face: its back faces point away from the viewer sphere and are
  // culled, so layer 1 is the +Z wall, 4 m away, and there is nothing behind that.
  ASSERT_EQ(layers.size(), 2u);
  const vec3 d = glm::normalize(vec3(0.1f, -0.05f, 1.0f));
  EXPECT_EQ(sample_cube(layers[0], d).object, box);
  EXPECT_NEAR(sample_cube(layers[0], d).distance, 1.5f * glm::length(d / d.z), 1e-2f);
  const CubeSample behind = sample_cube(layers[1], d);
  EXPECT_EQ(behind.object, 5u);  // wall_pz
  EXPECT_NEAR(behind.distance, 4.0f * glm::length(d / d.z), 1e-2f);
  // Where the room's wall is the first surface nothing lies behind it.
  EXPECT_TRUE(sample_cube(layers[1], vec3(1, 0.2f, -0.3f)).empty);
  // Without the culling the box's back face comes first.
  lo.cull_back_faces = false;
  const std::vector<DistanceCubeMap> all = render_distance_cube_layers(s, rays, vec3(0.0f), small(64), lo);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(sample_cube(all[1], d).object, box);
  EXPECT_NEAR(sample_cube(all[1], d).distance, 2.5f * glm::length(d / d.z), 1e-2f);
  EXPECT_EQ(sample_cube(all[2], d).object, 5u);
}

TEST(DistanceCubeLayers, ShadesOnlyTexelsAViewerCanReach) {
  uint32_t box = 0;
  Scene s = room_with_box(&box, 2.0f);
  RayScene rays(s);
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = 0.2f;
  lo.reachable_only = false;
  const size_t peeled = render_distance_cube_layers(s, rays, vec3(0.0f), small(256), lo)[1].shaded_texels;
  lo.reachable_only = true;
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(s, rays, vec3(0.0f), small(256), lo);
  ASSERT_EQ(layers.size(), 2u);
  const DistanceCubeMap& l1 = layers[1];
  EXPECT_EQ(l1.shaded_texels + l1.hidden_texels, peeled);
  // From within 0.2 m of c the wall behind the box's middle is out of reach (the box's
  // front face's edges, 1.8–2.1 m away, shift by at most asin(0.2/1.8) ≈ 6.4°, plus
  // 2 × 4° of tile radius; its middle is 33.7° in).
  EXPECT_GT(l1.hidden_texels, 0u);
  EXPECT_TRUE(sample_cube(l1, vec3(0, 0, 1)).empty);
  // Just inside the silhouette it is kept: the viewer sees past the edge there.
  EXPECT_FALSE(sample_cube(l1, glm::normalize(vec3(0.95f, 0, 1.5f))).empty);
  // A larger viewer sphere reaches farther in.
  lo.viewer_radius = 1.0f;
  EXPECT_GT(render_distance_cube_layers(s, rays, vec3(0.0f), small(256), lo)[1].shaded_texels, l1.shaded_texels);
}

TEST(DistanceCubeLayers, LayerCountIsBoundedNotOnePerObject) {
  // 60 boxes in three rings around c: the per-object layering made 61 maps.
  Scene s = box_room({-6, -6, -6}, {6, 6, 6});
  for (int i = 0; i < 60; ++i) {
    Mesh b = make_box(vec3(0.4f), 1);
    const float a = float(i) * 0.5f, radius = 1.5f + float(i % 3);
    transform_mesh(b, glm::translate(mat4(1.0f), vec3(radius * std::cos(a), float(i % 5) - 2.0f, radius * std::sin(a))));
    add_object(s, b, "box" + std::to_string(i), add_diffuse(s, vec3(0.5f)));
  }
  RayScene rays(s);
  const int res = 32;
  for (int k : {1, 2, 3}) {
    DistanceCubeLayerOptions lo;
    lo.layers = k;
    lo.viewer_radius = 1.0f;
    const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(s, rays, vec3(0.0f), small(res), lo);
    EXPECT_EQ(layers.size(), size_t(k));  // every peel finds something here
    for (const DistanceCubeMap& m : layers) EXPECT_LE(m.shaded_texels, size_t(6 * res * res));
  }
  DistanceCubeLayerOptions bad;
  bad.layers = 0;
  EXPECT_THROW(render_distance_cube_layers(s, rays, vec3(0.0f), small(res), bad), InputError);
  bad.layers = kMaxDistanceCubeLayers + 1;
  EXPECT_THROW(render_distance_cube_layers(s, rays, vec3(0.0f), small(res), bad), InputError);
}

TEST(DistanceCubeLayers, SameForAnyThreadCount) {
  uint32_t box = 0;
  Scene s = room_with_box(&box);
  AreaLight a;
  a.corner = {-0.5f, 3.9f, -0.5f};
  a.edge_u = {1, 0, 0};
  a.edge_v = {0, 0, 1};
  s.area_lights.push_back(a);
  RayScene rays(s);
  DistanceCubeMapOptions o = small(40);
  o.area_light_samples = 2;
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = 0.6f;
  std::vector<DistanceCubeMap> one, two;
  {
    ThreadLimit limit(1);
    one = render_distance_cube_layers(s, rays, vec3(0.1f), o, lo);
  }
  {
    ThreadLimit limit(2);
    two = render_distance_cube_layers(s, rays, vec3(0.1f), o, lo);
  }
  ASSERT_EQ(one.size(), two.size());
  ASSERT_GE(one.size(), 2u);
  for (size_t k = 0; k < one.size(); ++k)
    for (int f = 0; f < 6; ++f) {
      EXPECT_TRUE(one[k].faces[size_t(f)] == two[k].faces[size_t(f)]) << k << " " << f;
      EXPECT_TRUE(one[k].objects[size_t(f)] == two[k].objects[size_t(f)]) << k << " " << f;
    }
}

}  // namespace
}  // namespace proxima
