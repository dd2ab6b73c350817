// prepare_reflection_frame pinned bit for bit to the plain per-pixel computation: every
// reflection method, its Embree reference and the demo start from this frame, so a faster
// G-buffer pass must not change a bit of it. The specification below is the straightforward
// form — rasterize, then per pixel shade_reflected_point along the view ray; per reflective
// pixel the reference renderer's first-bounce rays — on built-in scenes (textures, point and
// area lights, mirrors and glossy lobes), a hand-made one with an environment cube map and
// several area lights, 1 and 2 samples per pixel, per-pixel and surface-cell lobe seeds,
// and 1 and 2 threads.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/hit_shading.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/shading.h"
#include "reflect_test_scenes.h"

namespace proxima {

namespace {

using reflect_test::add_diffuse;
using reflect_test::add_quad;

struct Facing {
  vec3 ng, n;
};
Facing plain_facing(const Scene& scene, uint32_t triangle, float u, float v, vec3 toward_viewer) {
  Facing f;
  f.ng = triangle_normal(scene, triangle);
  if (glm::dot(f.ng, toward_viewer) < 0.0f) f.ng = -f.ng;
  f.n = shading_normal(scene, triangle, u, v);
  if (glm::dot(f.n, f.ng) < 0.0f) f.n = -f.n;
  return f;
}

uint64_t cell_seed(uint64_t seed, vec3 p, float cell) {
  auto q = [&](float v) { return uint64_t(int64_t(std::clamp(std::floor(double(v) / double(cell)), -9e18, 9e18))); };
  return derive_seed(seed ^ 0x5EEDCE11ull, q(p.x), q(p.y), q(p.z));
}

// The frame computed pixel by pixel, in one thread: the specification.
ReflectionFrame plain_frame(const Scene& scene, const Camera& camera, const ReflectionOptions& o) {
  ReflectionFrame frame;
  const int k = o.supersample;
  frame.camera = camera;
  frame.supersample = k;
  frame.area_light_samples = o.area_light_samples;
  frame.sample_camera = camera;
  frame.sample_camera.width = camera.width * k;
  frame.sample_camera.height = camera.height * k;
  frame.scene_diagonal = std::max(scene_bounds(scene).diagonal(), 1e-3f);
  const float epsilon = kReflectionRayOffset * frame.scene_diagonal;
  RasterOptions ro;
  ro.outputs = kRasterTriangle | kRasterBarycentric | kRasterObject;
  const Camera& sc = frame.sample_camera;
  const RasterImages g = rasterize(scene, sc, ro);
  const int sw = sc.width, sh = sc.height;
  frame.base = ImageF(sw, sh, 3, 0.0f);
  for (int y = 0; y < sh; ++y)
    for (int x = 0; x < sw; ++x) {
      const uint32_t t = g.triangle.at(x, y);
      const vec3 dir = ray_through(sc, vec2(float(x) + 0.5f, float(y) + 0.5f)).dir;
      const vec3 c = t == kNoTriangle ? environment_radiance(scene.environment, dir)
                                      : shade_reflected_point(scene, t, g.barycentric.at(x, y, 0),
                                                              g.barycentric.at(x, y, 1), -dir, o.area_light_samples);
      for (int ch = 0; ch < 3; ++ch) frame.base.at(x, y, ch) = c[ch];
    }
  const float cell = o.lobe_seed_cell * frame.scene_diagonal;
  std::vector<vec2> lobe(size_t(o.glossy_rays));
  frame.first_ray.push_back(0);
  for (int y = 0; y < sh; ++y)
    for (int x = 0; x < sw; ++x) {
      const uint32_t t = g.triangle.at(x, y);
      if (t == kNoTriangle) continue;
      const Material& m = scene.materials[scene.triangle_material[t]];
      if (!m.reflective()) continue;
      frame.pixel.push_back(uint32_t(y) * uint32_t(sw) + uint32_t(x));
      frame.reflector.push_back(g.object.at(x, y));
      frame.specular.push_back(m.specular);
      frame.gloss.push_back(m.gloss);
      const float u = g.barycentric.at(x, y, 0), v = g.barycentric.at(x, y, 1);
      const vec3 dir = glm::normalize(ray_through(sc, vec2(float(x) + 0.5f, float(y) + 0.5f)).dir);
      const Facing f = plain_facing(scene, t, u, v, -dir);
      const vec3 p = triangle_point(scene, t, u, v);
      frame.position.push_back(p);
      frame.normal.push_back(f.n);
      frame.origin.push_back(p + epsilon * f.ng);
      const uint64_t out_pixel = uint64_t(y / k) * uint64_t(camera.width) + uint64_t(x / k);
      Pcg32 rng(cell > 0.0f ? cell_seed(o.seed, p, cell) : derive_seed(o.seed, out_pixel, uint64_t((y % k) * k + (x % k))));
      if (m.specular < 1.0f && surface_diffuse(scene, t, u, v) != vec3(0.0f))
        for (size_t l = 0; l < scene.area_lights.size(); ++l)
          for (int s = 0; s < 2 * o.area_light_samples * o.area_light_samples; ++s) rng.next_float();
      const vec3 mirror = reflect(dir, f.n);
      const float half_angle = glossy_lobe_half_angle(m.gloss);
      if (half_angle > 0.0f) {
        stratified_samples_2d(lobe, rng);
        for (const vec2& l : lobe) frame.direction.push_back(glossy_lobe_direction(mirror, f.ng, half_angle, l));
      } else {
        frame.direction.push_back(glossy_lobe_direction(mirror, f.ng, 0.0f, vec2(0.0f)));
      }
      frame.first_ray.push_back(uint32_t(frame.direction.size()));
    }
  return frame;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Success when `got` has every bit of `want`: the base image and every per-sample list.
testing::AssertionResult same_frame(const ReflectionFrame& want, const ReflectionFrame& got) {
  if (want.base.width() != got.base.width() || want.base.height() != got.base.height() || got.base.channels() != 3)
    return testing::AssertionFailure() << "base image sizes differ";
  size_t differ = 0, first = size_t(-1);
  const size_t n = size_t(want.base.width()) * size_t(want.base.height());
  for (size_t i = 0; i < n; ++i)
    if (std::memcmp(want.base.data().data() + 3 * i, got.base.data().data() + 3 * i, 3 * sizeof(float)) != 0) {
      if (differ++ == 0) first = i;
    }
  if (differ) return testing::AssertionFailure() << "base differs at " << differ << " of " << n << " pixels, first " << first;
  const std::pair<const char*, bool> lists[] = {
      {"pixel", same_bits(want.pixel, got.pixel)},          {"reflector", same_bits(want.reflector, got.reflector)},
      {"specular", same_bits(want.specular, got.specular)}, {"gloss", same_bits(want.gloss, got.gloss)},
      {"first_ray", same_bits(want.first_ray, got.first_ray)}, {"position", same_bits(want.position, got.position)},
      {"normal", same_bits(want.normal, got.normal)},       {"origin", same_bits(want.origin, got.origin)},
      {"direction", same_bits(want.direction, got.direction)}};
  for (const auto& [name, same] : lists)
    if (!same) return testing::AssertionFailure() << name << " differs";
  if (std::memcmp(&want.scene_diagonal, &got.scene_diagonal, sizeof(float)) != 0)
    return testing::AssertionFailure() << "scene_diagonal differs";
  return testing::AssertionSuccess();
}

// Success when prepare_reflection_frame equals plain_frame bit for bit at 1 and 2 samples per
// pixel side and on 1 and 2 threads, and the view shows a reflector (an empty frame proves nothing).
testing::AssertionResult equals_plain_frame(const Scene& scene, const Camera& camera, ReflectionOptions o) {
  for (int k : {1, 2}) {
    o.supersample = k;
    const ReflectionFrame want = plain_frame(scene, camera, o);
    if (want.sample_count() == 0) return testing::AssertionFailure() << scene.name << ": the view shows no reflector";
    for (int threads : {1, 2}) {
      ThreadLimit limit(threads);
      const testing::AssertionResult r = same_frame(want, prepare_reflection_frame(scene, camera, o));
      if (!r) return testing::AssertionFailure() << scene.name << " k=" << k << " threads=" << threads << ": " << r.message();
    }
  }
  return testing::AssertionSuccess();
}

Camera path_camera(const Scene& scene, const char* path_name, float at, int side) {
  const CameraPath& path = scene.camera_paths[size_t(find_camera_path(scene, path_name))];
  const float t = path.keys.front().time + at * (path.keys.back().time - path.keys.front().time);
  return camera_at_time(path, t, side, side, 0.01f, scene_far_plane(scene));
}

// Two walls and a glossy floor under a cube-map sky, two area lights (one facing away from
// part of the floor), a point light on the floor's plane, a black and an emissive material:
// the branches of the shading.
Scene sky_courtyard() {
  Scene s;
  s.name = "sky-courtyard";
  const uint32_t floor_mat = add_diffuse(s, vec3(0.4f, 0.5f, 0.6f), 0.6f);
  s.materials[floor_mat].gloss = 0.2f;
  add_quad(s, vec3(-3, 0, -3), vec3(0, 0, 6), vec3(6, 0, 0), floor_mat, "floor");
  add_quad(s, vec3(-3, 0, -3), vec3(6, 0, 0), vec3(0, 3, 0), add_diffuse(s, vec3(0.8f, 0.3f, 0.2f)), "back");
  add_quad(s, vec3(-3, 0, -3), vec3(0, 3, 0), vec3(0, 0, 6), add_diffuse(s, vec3(0.0f), 0.5f), "black-mirror");
  const uint32_t glow = add_diffuse(s, vec3(0.2f));
  s.materials[glow].emission = vec3(2.0f, 1.5f, 1.0f);
  add_quad(s, vec3(1, 0.01f, 0), vec3(0, 0, 1), vec3(1, 0, 0), glow, "glow");
  AreaLight a;
  a.corner = vec3(-1, 2.5f, -1);
  a.edge_u = vec3(1, 0, 0);
  a.edge_v = vec3(0, 0, 1);  // normal −Y: faces the floor
  a.radiance = vec3(3.0f);
  s.area_lights.push_back(a);
  AreaLight b;
  b.corner = vec3(2, 0.5f, -2);
  b.edge_u = vec3(0, 1, 0);
  b.edge_v = vec3(0, 0, 0.5f);
  b.radiance = vec3(1.0f, 2.0f, 4.0f);
  s.area_lights.push_back(b);
  s.point_lights.push_back({vec3(0.5f, 0.0f, 0.5f), vec3(2.0f)});
  s.point_lights.push_back({vec3(-1.0f, 1.5f, 2.0f), vec3(3.0f, 2.0f, 1.0f)});
  s.ambient = vec3(0.05f);
  for (int f = 0; f < 6; ++f) {
    s.environment.cube[size_t(f)] = ImageF(4, 4, 3, 0.0f);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c) s.environment.cube[size_t(f)].at(x, y, c) = 0.1f * float(f + 1) + 0.05f * float(x + y + c);
  }
  return s;
}

// compose_reflections as the plain box filter over base + s·reflected.
ImageF plain_compose(const ReflectionFrame& frame, const std::vector<vec3>& reflected) {
  ImageF samples = frame.base;
  const int sw = frame.sample_camera.width;
  for (size_t i = 0; i < frame.sample_count(); ++i)
    for (int c = 0; c < 3; ++c)
      samples.at(int(frame.pixel[i] % uint32_t(sw)), int(frame.pixel[i] / uint32_t(sw)), c) +=
          frame.specular[i] * reflected[i][c];
  const int k = frame.supersample;
  ImageF out(frame.camera.width, frame.camera.height, 3, 0.0f);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        float sum = 0.0f;
        for (int j = 0; j < k; ++j)
          for (int i = 0; i < k; ++i) sum += samples.at(x * k + i, y * k + j, c);
        out.at(x, y, c) = sum / float(k * k);
      }
  return out;
}

}  // namespace

TEST(ReflectionFrame, ComposeEqualsThePlainBoxFilter) {
  const Scene scene = sky_courtyard();
  const Camera camera = look_at(vec3(2.0f, 1.6f, 2.5f), vec3(-0.5f, 0.6f, -1.0f), vec3(0, 1, 0), 70.0f, 37, 29, 0.01f, 100.0f);
  for (int k : {1, 2, 3}) {
    ReflectionOptions o;
    o.supersample = k;
    ReflectionFrame frame = prepare_reflection_frame(scene, camera, o);
    ASSERT_GT(frame.sample_count(), 0u);
    frame.base.at(0, 0, 1) = -0.0f;  // the filter's 0 + (−0) is +0
    Pcg32 rng(7);
    std::vector<vec3> reflected(frame.sample_count());
    for (vec3& r : reflected) r = vec3(rng.next_float(), 3.0f * rng.next_float(), rng.next_float() - 0.5f);
    for (int threads : {1, 2}) {
      ThreadLimit limit(threads);
      const ImageF want = plain_compose(frame, reflected), got = compose_reflections(frame, reflected);
      ASSERT_EQ(want.data().size(), got.data().size());
      EXPECT_EQ(std::memcmp(want.data().data(), got.data().data(), want.data().size() * sizeof(float)), 0) << "k=" << k;
    }
  }
}

TEST(ReflectionFrame, LivingRoomEqualsThePlainPerPixelComputation) {
  const Scene scene = make_builtin_scene("living-room");
  ReflectionOptions o;
  o.glossy_rays = 8;
  EXPECT_TRUE(equals_plain_frame(scene, path_camera(scene, "walk", 0.21f, 48), o));
}

TEST(ReflectionFrame, BathroomAndCornellEqualThePlainPerPixelComputation) {
  const Scene bathroom = make_builtin_scene("bathroom");
  ReflectionOptions o;
  o.glossy_rays = 5;  // N-rooks lobe samples
  o.area_light_samples = 3;
  EXPECT_TRUE(equals_plain_frame(bathroom, path_camera(bathroom, "walk", 0.5f, 40), o));
  const Scene cornell = make_builtin_scene("cornell");
  o.glossy_rays = 4;
  o.area_light_samples = 2;
  Camera camera = cornell.cameras.front().camera;
  camera.width = 45;
  camera.height = 33;
  EXPECT_TRUE(equals_plain_frame(cornell, camera, o));
}

TEST(ReflectionFrame, CubeMapSkyAndSeveralAreaLightsEqualThePlainPerPixelComputation) {
  const Scene scene = sky_courtyard();
  const Camera camera = look_at(vec3(2.0f, 1.6f, 2.5f), vec3(-0.5f, 0.6f, -1.0f), vec3(0, 1, 0), 70.0f, 37, 29, 0.01f, 100.0f);
  ReflectionOptions o;
  o.glossy_rays = 9;
  EXPECT_TRUE(equals_plain_frame(scene, camera, o));
  o.lobe_seed_cell = 0.01f;
  o.area_light_samples = 1;
  EXPECT_TRUE(equals_plain_frame(scene, camera, o));
}

TEST(ReflectionFrame, IntoAReusedFrameEqualsAFreshOne) {
  // One frame through a walk, then other sizes, samples per pixel and a scene with other
  // reflectors: whatever the buffers held before, the result is the fresh frame's.
  const Scene living = make_builtin_scene("living-room"), bathroom = make_builtin_scene("bathroom");
  ReflectionOptions o;
  o.glossy_rays = 8;
  ReflectionFrame reused;
  const struct {
    const Scene* scene;
    float at;
    int side, k, rays;
  } steps[] = {{&living, 0.21f, 48, 1, 8}, {&living, 0.25f, 48, 1, 8},  {&living, 0.3f, 61, 1, 16},
               {&bathroom, 0.5f, 40, 2, 5}, {&bathroom, 0.6f, 40, 1, 5}, {&living, 0.21f, 48, 1, 8}};
  for (const auto& s : steps) {
    o.supersample = s.k;
    o.glossy_rays = s.rays;
    const Camera camera = path_camera(*s.scene, "walk", s.at, s.side);
    prepare_reflection_frame_into(*s.scene, camera, o, reused);
    const ReflectionFrame fresh = prepare_reflection_frame(*s.scene, camera, o);
    ASSERT_GT(fresh.sample_count(), 0u) << s.scene->name << " at " << s.at;
    EXPECT_TRUE(same_frame(fresh, reused)) << s.scene->name << " at " << s.at << " side " << s.side << " k " << s.k;
  }
}

// The Embree pass pinned to its plain form: per ray the closest hit shaded by
// shade_reflected_point (or the environment), each sample's mean in ray order, on scenes
// with point and area lights, mirrors, glossy lobes, textures and a cube-map sky, on 1 and 2
// threads; the hits kept per ray, and the listed-samples entry giving the same radiance.
TEST(ReflectionFrame, TraceEqualsThePlainPerRayShading) {
  const Scene living = make_builtin_scene("living-room"), bathroom = make_builtin_scene("bathroom");
  const Scene courtyard = sky_courtyard();
  ReflectionOptions o;
  const struct {
    const Scene* scene;
    Camera camera;
    int rays, light_samples;
  } cases[] = {
      {&living, path_camera(living, "walk", 0.21f, 48), 16, 4},
      {&bathroom, path_camera(bathroom, "walk", 0.5f, 40), 5, 3},
      {&courtyard, look_at(vec3(2.0f, 1.6f, 2.5f), vec3(-0.5f, 0.6f, -1.0f), vec3(0, 1, 0), 70.0f, 37, 29, 0.01f, 100.0f), 9, 2},
  };
  for (const auto& c : cases) {
    o.glossy_rays = c.rays;
    o.area_light_samples = c.light_samples;
    const ReflectionFrame frame = prepare_reflection_frame(*c.scene, c.camera, o);
    ASSERT_GT(frame.sample_count(), 0u) << c.scene->name;
    RayScene rays(*c.scene);
    std::vector<vec3> want(frame.sample_count());
    std::vector<uint32_t> want_triangle(frame.direction.size(), kNoTriangle);
    std::vector<float> want_t(frame.direction.size(), kInf);
    for (size_t i = 0; i < frame.sample_count(); ++i) {
      vec3 sum(0.0f);
      for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r) {
        const vec3 dir = frame.direction[r];
        const Hit hit = rays.intersect(Ray{frame.origin[i], dir, 0.0f, kInf});
        if (hit.valid()) {
          want_triangle[r] = hit.triangle, want_t[r] = hit.t;
          sum += shade_reflected_point(*c.scene, hit.triangle, hit.u, hit.v, -dir, frame.area_light_samples);
        } else {
          sum += environment_radiance(c.scene->environment, dir);
        }
      }
      want[i] = sum / float(frame.first_ray[i + 1] - frame.first_ray[i]);
    }
    std::vector<uint32_t> every(frame.sample_count());
    for (uint32_t i = 0; i < every.size(); ++i) every[i] = i;
    for (int threads : {1, 2}) {
      ThreadLimit limit(threads);
      const TracedReflections got = trace_reflections(*c.scene, rays, frame);
      EXPECT_TRUE(same_bits(want, got.radiance)) << c.scene->name << " threads=" << threads;
      EXPECT_TRUE(same_bits(want_triangle, got.hit_triangle)) << c.scene->name << " threads=" << threads;
      EXPECT_TRUE(same_bits(want_t, got.hit_t)) << c.scene->name << " threads=" << threads;
      std::vector<vec3> listed(frame.sample_count(), vec3(-1.0f));
      trace_reflection_samples(*c.scene, rays, frame, every, listed);
      EXPECT_TRUE(same_bits(want, listed)) << c.scene->name << " threads=" << threads;
    }
  }
}

}  // namespace proxima
