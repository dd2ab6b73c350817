// Screen-space reflections against Embree on the same rays: a planar mirror whose reflected
// surfaces are all on screen is answered by SSR alone within MAE 1 (0–255); where the reflected
// surfaces are off screen the rays fall back to the box probe, and are counted.
#include "proxima/reflect/hit_shading.h"
#include "proxima/reflect/ssr_reflection.h"

#include <gtest/gtest.h>

#include "proxima/core/parallel.h"
#include "proxima/eval/image_error.h"
#include "proxima/reflect/box_probe.h"
#include "proxima/reflect/envmap_frame_reflections.h"
#include "proxima/reflect/envmap_reflection.h"
#include "reflect_test_scenes.h"
#include "test_util.h"

namespace proxima {
namespace {

using reflect_test::add_diffuse;
using reflect_test::add_quad;
using reflect_test::box_room;

uint32_t mirror_material(Scene& s) {
  Material m;
  m.name = "mirror";
  m.diffuse = vec3(0.0f);
  m.specular = 1.0f;
  return add_material(s, m);
}

// A floor mirror in front of a striped back wall and a red panel standing behind it, seen
// from above the floor: every reflected ray meets the wall's or the panel's camera-facing side.
Scene mirror_before_wall() {
  Scene s;
  s.name = "mirror-before-wall";
  const vec3 stripes[4] = {{0.8f, 0.3f, 0.2f}, {0.2f, 0.7f, 0.3f}, {0.2f, 0.3f, 0.9f}, {0.9f, 0.9f, 0.3f}};
  for (int i = 0; i < 4; ++i)
    add_quad(s, vec3(-3.0f + 1.5f * float(i), -1.0f, -4.0f), vec3(1.5f, 0, 0), vec3(0, 4, 0),
             add_diffuse(s, stripes[i]), "wall" + std::to_string(i));
  add_quad(s, vec3(-3, -1, 0), vec3(6, 0, 0), vec3(0, 0, -4), add_diffuse(s, vec3(0.5f)), "floor");
  add_quad(s, vec3(-0.5f, -0.99f, -1.8f), vec3(1, 0, 0), vec3(0, 0, -2), mirror_material(s), "mirror");
  add_quad(s, vec3(-0.3f, -1.0f, -3.2f), vec3(0.6f, 0, 0), vec3(0, 0.8f, 0), add_diffuse(s, vec3(0.9f, 0.1f, 0.1f)),
           "panel");
  s.point_lights.push_back({vec3(0.0f, 2.0f, -2.0f), vec3(6.0f)});
  s.ambient = vec3(0.1f);
  return s;
}

struct SsrRun {
  ReflectionFrame frame;
  TracedReflections traced;
  SsrReflections ssr;
  double mae = 0.0;  // SSR vs Embree on the same rays, 0–255, over the reflective pixels
};

SsrRun run(const Scene& scene, const Camera& cam, const SsrFallback& fallback) {
  SsrRun r;
  const RayScene rays(scene);
  ReflectionOptions ro;
  ro.area_light_samples = 1;
  r.frame = prepare_reflection_frame(scene, cam, ro);
  r.traced = trace_reflections(scene, rays, r.frame);
  r.ssr = render_ssr_reflections(scene, r.frame, SsrOptions{}, fallback);
  const ImageU8 mask = reflective_pixel_mask(r.frame);
  r.mae = compare_images(compose_reflections(r.frame, r.ssr.radiance), compose_reflections(r.frame, r.traced.radiance),
                         &mask)
              .mae_avg;
  return r;
}

TEST(SsrReflection, PlanarMirrorWithEverythingOnScreenIsWithinMae1OfEmbree) {
  const Scene scene = mirror_before_wall();
  const Camera cam = look_at(vec3(0.0f), vec3(0.0f, -0.15f, -1.0f), vec3(0, 1, 0), 60.0f, 128, 128);
  const SsrRun r = run(scene, cam, {});
  ASSERT_GT(r.frame.sample_count(), 2000u);
  const SsrStats& st = r.ssr.stats;
  RecordProperty("ssr_mae", std::to_string(r.mae));
  RecordProperty("fallback_samples", std::to_string(st.fallback_samples) + " of " + std::to_string(st.samples));
  RecordProperty("steps_per_ray", std::to_string(double(st.steps) / double(st.rays)));
  EXPECT_LT(r.mae, 1.0) << "0–255 display scale";
  // SSR answered: nearly every ray hit, and the fallback (here the environment: black) is unused.
  EXPECT_GT(double(st.outcome_rays[size_t(SsrOutcome::Hit)]), 0.99 * double(st.rays));
  EXPECT_LT(double(st.fallback_samples), 0.01 * double(st.samples)) << st.fallback_samples;
  EXPECT_LT(double(st.steps) / double(st.rays), 200.0);
}

// A floor mirror seen from above: its rays go up to the ceiling and walls, which the camera
// (looking down) does not see. They fall back to the box probe of the room.
TEST(SsrReflection, OffScreenReflectionsFallBackToTheBoxProbeAndAreCounted) {
  Scene scene = box_room(vec3(-2, 0, -3), vec3(2, 2.5f, 3));
  add_quad(scene, vec3(-1.0f, 0.01f, 1.0f), vec3(2, 0, 0), vec3(0, 0, -2), mirror_material(scene), "mirror");
  const Camera cam = look_at(vec3(0.0f, 1.2f, 1.6f), vec3(0.0f), vec3(0, 1, 0), 45.0f, 96, 96);
  const RayScene rays(scene);
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  DistanceCubeMapOptions mo;
  mo.resolution = 128;
  mo.area_light_samples = 1;
  mo.exclude = reflectors;
  mo.shade = [&](uint32_t tri, float u, float v, vec3 toward) { return shade_reflected_point(scene, tri, u, v, toward, 1); };
  const DistanceCubeMap map = render_distance_cube_map(scene, rays, projection_center(scene, reflectors), mo);
  const SsrFallback probe{&map, probe_proxy_box(scene)};
  const SsrRun with_probe = run(scene, cam, probe);
  const SsrRun with_env = run(scene, cam, {});
  const SsrStats& st = with_probe.ssr.stats;
  ASSERT_GT(st.samples, 1000u);
  EXPECT_GT(st.outcome_rays[size_t(SsrOutcome::OffScreen)], st.rays / 2);
  EXPECT_GT(double(st.fallback_samples), 0.5 * double(st.samples));
  // The count is the samples whose rays took the fallback; those with confidence 0 are the probe's.
  EnvmapInputs box_inputs;
  box_inputs.method = EnvmapMethod::BoxProbe;
  box_inputs.map = &map;
  box_inputs.box = probe.box;
  const std::vector<vec3> box = envmap_frame_reflections(scene, with_probe.frame, box_inputs);
  size_t counted = 0, zero = 0;
  for (size_t i = 0; i < st.samples; ++i) {
    counted += with_probe.ssr.confidence[i] < 1.0f;
    if (with_probe.ssr.confidence[i] != 0.0f) continue;
    ++zero;
    EXPECT_EQ(with_probe.ssr.radiance[i], box[i]) << i;
  }
  EXPECT_EQ(counted, st.fallback_samples);
  EXPECT_GT(zero, st.samples / 2);
  // The probe answers the walls and ceiling nearly exactly; the environment (black) does not.
  RecordProperty("ssr_probe_mae", std::to_string(with_probe.mae));
  RecordProperty("ssr_env_mae", std::to_string(with_env.mae));
  RecordProperty("fallback_samples", std::to_string(st.fallback_samples) + " of " + std::to_string(st.samples));
  EXPECT_LT(with_probe.mae, 2.0);
  EXPECT_GT(with_env.mae, 10.0 * with_probe.mae) << with_env.mae << " vs " << with_probe.mae;
}

TEST(SsrReflection, SameResultForAnyThreadCount) {
  const Scene scene = mirror_before_wall();
  const Camera cam = look_at(vec3(0.3f, 0.0f, 0.0f), vec3(0.0f, -0.3f, -1.0f), vec3(0, 1, 0), 60.0f, 64, 64);
  ReflectionOptions ro;
  ro.area_light_samples = 1;
  const ReflectionFrame frame = prepare_reflection_frame(scene, cam, ro);
  SsrReflections a, b;
  {
    ThreadLimit limit(1);
    a = render_ssr_reflections(scene, frame, {}, {});
  }
  {
    ThreadLimit limit(2);
    b = render_ssr_reflections(scene, frame, {}, {});
  }
  EXPECT_EQ(a.radiance, b.radiance);
  EXPECT_EQ(a.stats.steps, b.stats.steps);
  EXPECT_EQ(a.stats.fallback_samples, b.stats.fallback_samples);
}

TEST(SsrReflection, OptionsOutOfRangeAreRefused) {
  SsrOptions o;
  o.max_steps = 0;
  EXPECT_NE(error_of([&] { validate(o); }).find("ssr max_steps"), std::string::npos);
  o = {};
  o.edge_fade = 0.7f;
  EXPECT_NE(error_of([&] { validate(o); }).find("ssr edge_fade"), std::string::npos);
  o = {};
  o.min_thickness = 0.0f;
  EXPECT_NE(error_of([&] { validate(o); }).find("ssr min_thickness"), std::string::npos);
}

}  // namespace
}  // namespace proxima
