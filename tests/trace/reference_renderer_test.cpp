#include "proxima/trace/reference_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/shading.h"
#include "trace/test_geometry.h"

namespace proxima {
namespace {

using test::add_diffuse;
using test::quad_mesh;
using test::sphere_mesh;

vec3 pixel_rgb(const ImageF& img, int x, int y) {
  return vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
}

// Ray/sphere entry distance along unit d, or nullopt.
std::optional<float> hit_sphere(vec3 o, vec3 d, vec3 c, float r) {
  vec3 oc = o - c;
  float b = glm::dot(oc, d);
  float disc = b * b - (glm::dot(oc, oc) - r * r);
  if (disc < 0.0f) return std::nullopt;
  float t = -b - std::sqrt(disc);
  return t > 0.0f ? std::optional<float>(t) : std::nullopt;
}

TEST(ReferenceItemBuffer, AgreesWithAnalyticProjectionOfAQuad) {
  // Quad in the plane z = 0: x ∈ [−1, 1], y ∈ [−0.5, 0.5], seen obliquely.
  Scene s;
  add_object(s, quad_mesh(vec3(-1, -0.5f, 0), vec3(2, 0, 0), vec3(0, 1, 0)), "quad",
             add_diffuse(s, vec3(0.5f)));
  RayScene rays(s);
  const vec3 eye(0.4f, 0.3f, 2.5f), target(0.1f, 0.0f, 0.0f);
  Camera cam = look_at(eye, target, vec3(0, 1, 0), 50.0f, 64, 48);
  ItemBuffer ib = trace_item_buffer(s, rays, cam);
  ASSERT_EQ(ib.depth.width(), 64);
  ASSERT_EQ(ib.normal.channels(), 3);
  // Independent pinhole model: basis from look_at, focal length from the fov.
  vec3 f = glm::normalize(target - eye);
  vec3 r = glm::normalize(glm::cross(f, vec3(0, 1, 0)));
  vec3 u = glm::cross(r, f);
  float focal = 24.0f / std::tan(glm::radians(25.0f));
  int hits = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      vec3 d =
          glm::normalize(f + (float(x) + 0.5f - 32.0f) / focal * r - (float(y) + 0.5f - 24.0f) / focal * u);
      float t = -eye.z / d.z;
      vec3 p = eye + t * d;
      float margin = std::min(1.0f - std::abs(p.x), 0.5f - std::abs(p.y));
      if (std::abs(margin) < 0.01f) continue;  // too close to the edge to call
      if (margin > 0.0f) {
        ++hits;
        ASSERT_LT(ib.triangle.at(x, y), 2u) << x << "," << y;
        EXPECT_NEAR(ib.depth.at(x, y), glm::dot(p - eye, f), 1e-5f);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ib.position.at(x, y, c), p[c], 1e-5f);
        EXPECT_EQ(ib.normal.at(x, y, 2), 1.0f);  // facing the camera (+Z side)
        // And the hit point projects back to this pixel's center.
        std::optional<Projection> proj = project(cam, p);
        ASSERT_TRUE(proj);
        EXPECT_NEAR(proj->pixel.x, float(x) + 0.5f, 1e-3f);
        EXPECT_NEAR(proj->pixel.y, float(y) + 0.5f, 1e-3f);
        vec3 q =
            triangle_point(s, ib.triangle.at(x, y), ib.barycentric.at(x, y, 0), ib.barycentric.at(x, y, 1));
        EXPECT_NEAR(glm::distance(q, p), 0.0f, 1e-5f);
      } else {
        EXPECT_EQ(ib.triangle.at(x, y), kNoTriangle);
        EXPECT_EQ(ib.depth.at(x, y), kInf);
        EXPECT_EQ(ib.normal.at(x, y, 0), 0.0f);
      }
    }
  EXPECT_GT(hits, 500);
}

TEST(ReferenceItemBuffer, NormalFacesTheCamera) {
  Scene s;
  add_object(s, quad_mesh(vec3(-1, -1, 0), vec3(2, 0, 0), vec3(0, 2, 0)), "quad", add_diffuse(s, vec3(0.5f)));
  RayScene rays(s);
  Camera cam = look_at(vec3(0, 0, -2), vec3(0), vec3(0, 1, 0), 40.0f, 8, 8);  // sees the back
  ItemBuffer ib = trace_item_buffer(s, rays, cam);
  EXPECT_EQ(ib.normal.at(4, 4, 2), -1.0f);
  EXPECT_NEAR(ib.depth.at(4, 4), 2.0f, 1e-5f);
  // Vertex normals that contradict the winding are flipped too.
  for (vec3& n : s.normals) n = -n;
  EXPECT_EQ(trace_item_buffer(s, rays, cam).normal.at(4, 4, 2), -1.0f);
  Camera front = look_at(vec3(0, 0, 2), vec3(0), vec3(0, 1, 0), 40.0f, 8, 8);
  EXPECT_EQ(trace_item_buffer(s, rays, front).normal.at(4, 4, 2), 1.0f);
}

// Large diffuse floor y = 0, point light above, optional occluder square at y = 1.
Scene lit_floor(vec3 albedo, bool occluder) {
  Scene s;
  add_object(s, quad_mesh(vec3(-10, 0, 10), vec3(20, 0, 0), vec3(0, 0, -20)), "floor",
             add_diffuse(s, albedo));
  if (occluder)
    add_object(s, quad_mesh(vec3(-0.2f, 1, 0.2f), vec3(0.4f, 0, 0), vec3(0, 0, -0.4f)), "occluder", 0);
  s.point_lights.push_back(PointLight{vec3(0.3f, 2.0f, -0.2f), vec3(10, 20, 5)});
  s.ambient = vec3(0.05f, 0.1f, 0.02f);
  return s;
}

TEST(ReferenceRender, DiffusePlaneUnderPointLightMatchesKnownAnswer) {
  const vec3 albedo(0.5f, 0.25f, 0.8f);
  Scene s = lit_floor(albedo, true);
  RayScene rays(s);
  Camera cam = look_at(vec3(0, 3, 3), vec3(0), vec3(0, 1, 0), 60.0f, 48, 48);
  ItemBuffer ib = trace_item_buffer(s, rays, cam);
  ImageF img = render_reference(s, rays, cam, ReferenceOptions{});
  const PointLight& light = s.point_lights[0];
  int lit = 0, shadowed = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      if (ib.triangle.at(x, y) >= 2) continue;  // sky or the occluder itself
      vec3 p(ib.position.at(x, y, 0), ib.position.at(x, y, 1), ib.position.at(x, y, 2));
      // The segment to the light crosses y = 1 halfway.
      vec3 mid = 0.5f * (p + light.position);
      float margin = 0.2f - std::max(std::abs(mid.x), std::abs(mid.z));
      if (std::abs(margin) < 0.01f) continue;
      vec3 expected = s.ambient * albedo;
      if (margin < 0.0f) {
        vec3 to_light = light.position - p;
        float r2 = glm::dot(to_light, to_light);
        float cos_theta = to_light.y / std::sqrt(r2);
        expected += albedo / kPi * light.intensity * cos_theta / r2;
        ++lit;
      } else {
        ++shadowed;
      }
      vec3 got = pixel_rgb(img, x, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-4f * expected[c]) << x << "," << y;
    }
  EXPECT_GT(lit, 500);
  EXPECT_GT(shadowed, 10);
}

TEST(ReferenceRender, MirrorAndGlossyFloorReflectTheEnvironment) {
  Scene s;
  add_object(s, quad_mesh(vec3(-10, 0, 10), vec3(20, 0, 0), vec3(0, 0, -20)), "floor",
             add_diffuse(s, vec3(0.0f), 1.0f, 0.0f));
  s.environment.color = vec3(0.2f, 0.4f, 0.6f);
  s.point_lights.push_back(PointLight{vec3(0, 2, 0), vec3(5)});
  RayScene rays(s);
  Camera cam = look_at(vec3(0, 1, 3), vec3(0, 0, 0), vec3(0, 1, 0), 60.0f, 24, 24);
  ReferenceOptions o;
  ImageF mirror = render_reference(s, rays, cam, o);
  for (float v : mirror.data()) ASSERT_TRUE(v == 0.2f || v == 0.4f || v == 0.6f);
  s.materials[0].gloss = 0.7f;
  o.glossy_rays = 9;
  ImageF glossy = render_reference(s, rays, cam, o);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(glossy.at(x, y, c), s.environment.color[c], 1e-6f);
  // No bounces: the floor loses its reflection; the sky stays.
  o.max_bounces = 0;
  ImageF none = render_reference(s, rays, cam, o);
  EXPECT_EQ(pixel_rgb(none, 12, 23), vec3(0.0f));
  EXPECT_EQ(pixel_rgb(none, 12, 0), s.environment.color);
}

TEST(ReferenceRender, EmissionIsVisible) {
  Scene s;
  add_object(s, quad_mesh(vec3(-1, 0, -1), vec3(2, 0, 0), vec3(0, 2, 0)), "emitter",
             add_diffuse(s, vec3(0.0f), 0.0f, 0.0f, vec3(3, 2, 1)));
  RayScene rays(s);
  Camera cam = look_at(vec3(0, 1, 2), vec3(0, 1, -1), vec3(0, 1, 0), 30.0f, 8, 8);
  ImageF img = render_reference(s, rays, cam, ReferenceOptions{});
  EXPECT_EQ(pixel_rgb(img, 4, 4), vec3(3, 2, 1));
}

TEST(ReferenceRender, BitIdenticalForOneAndTwoThreads) {
  Scene s = lit_floor(vec3(0.6f), true);
  add_object(s, sphere_mesh(vec3(0.5f, 0.5f, 0), 0.5f, 32, 16), "sphere",
             add_diffuse(s, vec3(0.3f), 0.6f, 0.4f));
  s.area_lights.push_back(AreaLight{vec3(-1, 2.5f, -1), vec3(0, 0, 1), vec3(1, 0, 0), vec3(4)});
  s.environment.color = vec3(0.1f, 0.2f, 0.3f);
  RayScene rays(s);
  Camera cam = look_at(vec3(0, 2, 3), vec3(0, 0.3f, 0), vec3(0, 1, 0), 55.0f, 40, 32);
  ReferenceOptions o;
  o.supersample = 2;
  o.area_light_samples = 2;
  o.glossy_rays = 5;
  o.seed = 42;
  ImageF one, two;
  {
    ThreadLimit limit(1);
    one = render_reference(s, rays, cam, o);
  }
  {
    ThreadLimit limit(2);
    two = render_reference(s, rays, cam, o);
  }
  EXPECT_TRUE(one == two);
  // Another seed changes the soft shadows and the glossy lobe.
  o.seed = 43;
  EXPECT_FALSE(render_reference(s, rays, cam, o) == one);
}

// The Cornell box of builtin_scenes.h, built by hand: interior x ∈ [−1, 1], y ∈ [0, 2],
// z ∈ [−1, 1], open at z = +1; left wall red, right wall green, the rest white; a mirror
// sphere of radius 0.4 at (−0.4, 0.4, −0.2); a point light under the ceiling.
Scene hand_cornell() {
  Scene s;
  uint32_t white = add_diffuse(s, vec3(0.75f));
  uint32_t red = add_diffuse(s, vec3(0.75f, 0.1f, 0.1f));
  uint32_t green = add_diffuse(s, vec3(0.1f, 0.75f, 0.1f));
  uint32_t mirror = add_diffuse(s, vec3(0.0f), 1.0f, 0.0f);
  add_object(s, quad_mesh(vec3(-1, 0, 1), vec3(2, 0, 0), vec3(0, 0, -2)), "floor", white);
  add_object(s, quad_mesh(vec3(-1, 2, -1), vec3(2, 0, 0), vec3(0, 0, 2)), "ceiling", white);
  add_object(s, quad_mesh(vec3(-1, 0, -1), vec3(2, 0, 0), vec3(0, 2, 0)), "back", white);
  add_object(s, quad_mesh(vec3(-1, 0, 1), vec3(0, 0, -2), vec3(0, 2, 0)), "left", red);
  add_object(s, quad_mesh(vec3(1, 0, -1), vec3(0, 0, 2), vec3(0, 2, 0)), "right", green);
  add_object(s, sphere_mesh(vec3(-0.4f, 0.4f, -0.2f), 0.4f, 128, 64), "mirror sphere", mirror);
  s.point_lights.push_back(PointLight{vec3(0, 1.8f, 0.2f), vec3(3.0f)});
  s.ambient = vec3(0.02f);
  return s;
}

// Finds, analytically, a pixel whose center sees the mirror sphere reflect the wall x =
// wall_x far from the wall's edges; checks that the rendered pixel is dominated by channel
// `dominant` and matches what a probe camera on the sphere looking along the mirror
// direction sees (both with 8×8 area-light samples, so sampling noise stays well under the
// tolerance).
void expect_mirror_reflects_wall(const Scene& s, float wall_x, int dominant) {
  const vec3 center(-0.4f, 0.4f, -0.2f);
  const float radius = 0.4f;
  Camera cam = look_at(vec3(0, 1, 3.5f), vec3(0, 1, 0), vec3(0, 1, 0), 40.0f, 160, 120);
  RayScene rays(s);
  float best_margin = 0.0f;
  int bx = -1, by = -1;
  vec3 best_p(0.0f), best_r(0.0f);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      Ray ray = ray_through(cam, vec2(float(x) + 0.5f, float(y) + 0.5f));
      std::optional<float> t = hit_sphere(ray.origin, ray.dir, center, radius);
      if (!t) continue;
      vec3 p = ray.origin + *t * ray.dir;
      vec3 n = (p - center) / radius;
      if (glm::dot(-ray.dir, n) < 0.3f) continue;  // keep away from the silhouette
      vec3 r = reflect(ray.dir, n);
      if (r.x * wall_x <= 0.0f) continue;
      vec3 q = p + (wall_x - p.x) / r.x * r;
      float margin = std::min({q.y, 2.0f - q.y, q.z + 1.0f, 1.0f - q.z});
      if (margin <= best_margin) continue;
      // Nothing else in the scene may stand between the sphere and the wall.
      Hit hit = rays.intersect(Ray{p + 1e-3f * n, r, 0.0f, kInf});
      if (!hit.valid() || std::abs(triangle_point(s, hit.triangle, hit.u, hit.v).x - wall_x) > 1e-3f)
        continue;
      best_margin = margin;
      bx = x, by = y, best_p = p, best_r = r;
    }
  ASSERT_GT(best_margin, 0.15f) << "no pixel reflects the wall x = " << wall_x;
  ReferenceOptions o;
  o.area_light_samples = 8;
  ImageF img = render_reference(s, rays, cam, o);
  vec3 got = pixel_rgb(img, bx, by);
  for (int c = 0; c < 3; ++c) {
    if (c != dominant) {
      EXPECT_GT(got[dominant], 2.0f * got[c]) << bx << "," << by;
    }
  }
  vec3 up = std::abs(best_r.y) < 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0);
  Camera probe = look_at(best_p, best_p + best_r, up, 1.0f, 1, 1);
  vec3 seen = pixel_rgb(render_reference(s, rays, probe, o), 0, 0);
  // A perfect mirror shows only what it reflects (plus its emission).
  Hit hit = rays.intersect(ray_through(cam, vec2(float(bx) + 0.5f, float(by) + 0.5f)));
  ASSERT_TRUE(hit.valid());
  const Material& m = s.materials[s.triangle_material[hit.triangle]];
  ASSERT_EQ(m.specular, 1.0f);
  vec3 expected = m.emission + seen;
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], expected[c], 0.05f * expected[c] + 1e-3f) << bx << "," << by;
}

TEST(ReferenceRender, HandBuiltCornellMirrorSphereReflectsTheSideWalls) {
  Scene s = hand_cornell();
  expect_mirror_reflects_wall(s, 1.0f, 1);   // green
  expect_mirror_reflects_wall(s, -1.0f, 0);  // red
}

// The built-in scene: same box and sphere, plus a glossy block, an area light and its
// emissive quad (the search skips pixels whose reflection the block hides).
TEST(ReferenceRender, CornellMirrorSphereReflectsTheSideWalls) {
  Scene s = make_builtin_scene("cornell");
  expect_mirror_reflects_wall(s, 1.0f, 1);   // green
  expect_mirror_reflects_wall(s, -1.0f, 0);  // red
}

TEST(ReferenceRender, RejectsBadOptions) {
  Scene s = lit_floor(vec3(0.5f), false);
  RayScene rays(s);
  Camera cam = look_at(vec3(0, 1, 3), vec3(0), vec3(0, 1, 0), 60.0f, 4, 4);
  ReferenceOptions o;
  o.supersample = 0;
  EXPECT_THROW(render_reference(s, rays, cam, o), InputError);
  o = ReferenceOptions{};
  o.max_bounces = -1;
  EXPECT_THROW(render_reference(s, rays, cam, o), InputError);
}

}  // namespace
}  // namespace proxima
