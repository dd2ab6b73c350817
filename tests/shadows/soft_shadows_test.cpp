// Soft shadows (thesis ch. 3, Algorithm 5): light setup, shadow-map visibility against
// exact Embree rays on a known scene, the §3.4.2 errors, reconstructed occluders close to
// the geometry, and thread-count independence.
#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/procedural.h"
#include "proxima/shadows/light_visibility.h"
#include "proxima/shadows/occluders.h"
#include "proxima/shadows/shadow_error.h"

namespace proxima {
namespace {

// Ground 4×4 m at y = 0, a 1×1 m box standing on it, a point light 3 m up.
Scene box_scene() {
  Scene s;
  Material m;
  m.diffuse = vec3(0.5f);
  const uint32_t mat = add_material(s, m);
  add_object(s, make_plane(4.0f, 4.0f, 1, 1), "ground", mat);
  Mesh box = make_box(vec3(1.0f), 1);
  transform_mesh(box, glm::translate(mat4(1.0f), vec3(0, 0.5f, 0)));
  add_object(s, box, "box", mat);
  s.point_lights.push_back(PointLight{vec3(0, 3, 0), vec3(10)});
  return s;
}

Camera box_view(int res) { return look_at(vec3(0, 4.0f, 3.0f), vec3(0), vec3(0, 1, 0), 60.0f, res, res, 0.05f, 50.0f); }

TEST(SoftShadows, LightIsAHorizontalSquareSizedByTheSceneDiagonal) {
  const Scene s = box_scene();
  const AreaLight light = shadow_light(s, 0.5f);
  const std::vector<vec3> c = light_corners(light);
  EXPECT_NEAR(glm::length(c[2] - c[0]), 0.5f * scene_bounds(s).diagonal(), 1e-4f);
  EXPECT_NEAR(glm::length(light.point(0.5f, 0.5f) - vec3(0, 3, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(light.normal().y, -1.0f, 1e-6f);
  const std::vector<vec3> samples = light_samples(light, 4).points;
  ASSERT_EQ(samples.size(), 16u);
  EXPECT_NEAR(samples[0].x, c[0].x + light.edge_u.x / 8.0f, 1e-5f);
}

struct LightSetup {
  Scene scene = box_scene();
  AreaLight light;
  LightSamples samples;
  Receivers receivers;
  LightCameras cams;
  explicit LightSetup(float size, int n, int res) {
    light = shadow_light(scene, size);
    samples = light_samples(light, n);
    receivers = render_receivers(scene, box_view(res));
    std::vector<vec3> eyes = samples.points;
    for (const vec3& c : light_corners(light)) eyes.push_back(c);
    cams = fit_light_cameras(scene, light, receivers, eyes);
  }
};

TEST(SoftShadows, ShadowMapsAgreeWithShadowRays) {
  LightSetup s(0.3f, 4, 64);
  const RayScene rays(s.scene);
  ShadowMapOptions o;
  o.resolution = 256;
  const LightVisibility maps = shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, o);
  const LightVisibility exact = ray_visibility(rays, s.scene, s.receivers, s.samples);
  const ShadowError e = compare_visibility(maps, exact, s.receivers);
  EXPECT_LT(e.visibility_mean, 4.0);  // of 255: shadow-map aliasing at the edges only
  // The box shadows the ground right beside it: some pixels see few samples, others all.
  int dark = 0, lit = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (s.receivers.mask.at(x, y)) {
        dark += exact.lit_count(x, y) == 0;
        lit += exact.lit_count(x, y) == 16;
      }
  EXPECT_GT(dark, 20);
  EXPECT_GT(lit, 200);
}

// The light inside a room (as in a furnished house): the ceiling above the light's plane is
// behind the one-sided light, so no sample lights it, for the maps and the rays alike, and
// no receiver falls outside its fitted map.
TEST(SoftShadows, ReceiversBehindTheLightAreUnlitForEveryMethod) {
  Scene scene = box_scene();
  Material m;
  m.diffuse = vec3(0.5f);
  Mesh ceiling = make_plane(4.0f, 4.0f, 1, 1);
  transform_mesh(ceiling, glm::translate(mat4(1.0f), vec3(0, 4, 0)) *
                              glm::rotate(mat4(1.0f), glm::pi<float>(), vec3(1, 0, 0)));  // faces down
  add_object(scene, ceiling, "ceiling", add_material(scene, m));
  const AreaLight light = shadow_light(scene, 0.2f);  // around the point light at y = 3
  const LightSamples samples = light_samples(light, 4);
  const Receivers receivers =
      render_receivers(scene, look_at(vec3(0, 2, 3.5f), vec3(0, 2, 0), vec3(0, 1, 0), 100.0f, 64, 64, 0.05f, 50.0f));
  std::vector<vec3> eyes = samples.points;
  for (const vec3& c : light_corners(light)) eyes.push_back(c);
  const LightCameras cams = fit_light_cameras(scene, light, receivers, eyes);
  ShadowMapOptions o;
  o.resolution = 256;
  ShadowMapStats st;
  const LightVisibility maps = shadow_map_visibility(scene, receivers, samples, cams, o, nullptr, &st);
  const RayScene rays(scene);
  const LightVisibility exact = ray_visibility(rays, scene, receivers, samples);
  EXPECT_EQ(st.receivers_outside, 0u);
  int behind = 0, lit_below = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      if (!receivers.mask.at(x, y)) continue;
      if (receivers.position.at(x, y, 1) > 3.0f) {
        ++behind;
        EXPECT_EQ(maps.lit_count(x, y), 0) << x << "," << y;
        EXPECT_EQ(exact.lit_count(x, y), 0) << x << "," << y;
      } else {
        lit_below += exact.lit_count(x, y) > 0;
      }
    }
  EXPECT_GT(behind, 300);
  EXPECT_GT(lit_below, 300);
  EXPECT_LT(compare_visibility(maps, exact, receivers).visibility_mean, 4.0);
}

TEST(SoftShadows, ErrorsCountWrongSamplesAndColourTheirSign) {
  LightSetup s(0.3f, 2, 8);
  LightVisibility truth(8, 8, 4), approx(8, 8, 4);
  // Pixel (1, 1): truth sees samples 0, 1; approx sees 1, 2, 3 → 3 wrong, one too many lit.
  truth.bits[size_t(1 * 8 + 1)] = 0b0011;
  approx.bits[size_t(1 * 8 + 1)] = 0b1110;
  // Pixel (2, 1): truth sees all, approx none → too dark.
  truth.bits[size_t(1 * 8 + 2)] = 0b1111;
  Receivers r = s.receivers;
  r.mask = ImageU8(8, 8, 1, 1);
  const ShadowError e = compare_visibility(approx, truth, r);
  EXPECT_DOUBLE_EQ(e.visibility_max, 255.0);
  EXPECT_DOUBLE_EQ(e.intensity_max, 255.0);
  EXPECT_DOUBLE_EQ(e.visibility_mean, (3 * 255.0 / 4 + 255.0) / 64);
  EXPECT_DOUBLE_EQ(e.intensity_mean, (255.0 / 4 + 255.0) / 64);
  EXPECT_GT(e.image.at(1, 1, 1), 0.0f);  // too bright: green
  EXPECT_EQ(e.image.at(1, 1, 0), 0.0f);
  EXPECT_GT(e.image.at(2, 1, 0), 0.0f);  // too dark: red
  EXPECT_EQ(e.image.at(2, 1, 1), 0.0f);
  EXPECT_EQ(compare_visibility(truth, truth, r).visibility_max, 0.0);
}

TEST(SoftShadows, ReconstructedOccludersCastTheGeometrysShadow) {
  LightSetup s(0.3f, 4, 64);
  ShadowMapOptions sm;
  sm.resolution = 256;
  const LightVisibility truth = shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, sm);
  OccluderOptions o;
  o.resolution = 128;
  for (ShadowSampling sampling : {ShadowSampling::Nrr, ShadowSampling::Conventional, ShadowSampling::Peeling}) {
    const Occluders occ = build_occluders(s.scene, nullptr, s.light, s.cams, sampling, o);
    EXPECT_GT(occ.samples, 1000u) << shadow_sampling_name(sampling);
    const LightVisibility v = shadow_map_visibility(occ.scene, s.receivers, s.samples, s.cams, sm);
    const ShadowError e = compare_visibility(v, truth, s.receivers);
    EXPECT_LT(e.visibility_mean, 5.0) << shadow_sampling_name(sampling);
  }
  const Occluders geometry = build_occluders(s.scene, nullptr, s.light, s.cams, ShadowSampling::Geometry, o);
  EXPECT_EQ(geometry.scene.triangles.size(), s.scene.triangles.size());
}

TEST(SoftShadows, SameVisibilityForAnyThreadCount) {
  LightSetup s(0.5f, 3, 48);
  ShadowMapOptions sm;
  sm.resolution = 128;
  const RayScene rays(s.scene);
  LightVisibility a, b, c, d;
  {
    ThreadLimit one(1);
    a = shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, sm);
    c = ray_visibility(rays, s.scene, s.receivers, s.samples);
  }
  {
    ThreadLimit two(2);
    b = shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, sm);
    d = ray_visibility(rays, s.scene, s.receivers, s.samples);
  }
  EXPECT_EQ(a.bits, b.bits);
  EXPECT_EQ(c.bits, d.bits);
}

// A fitted map holds every receiver, keeps the requested texel density, and its far plane
// lies behind the farthest receiver.
TEST(SoftShadows, FittedMapCameraHoldsEveryReceiver) {
  LightSetup s(0.5f, 3, 48);
  std::vector<vec3> points;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x)
      if (s.receivers.mask.at(x, y))
        points.push_back(vec3(s.receivers.position.at(x, y, 0), s.receivers.position.at(x, y, 1),
                              s.receivers.position.at(x, y, 2)));
  ASSERT_GT(points.size(), 1000u);
  const float focal = 200.0f;
  for (const vec3& eye : s.samples.points) {
    const Camera cam = fitted_shadow_map_camera(s.cams, eye, points, focal);
    EXPECT_NEAR(focal_length_px(cam), focal, 1e-3f * focal);
    EXPECT_LT(cam.vfov_deg, s.cams.vfov_deg);  // the receivers fill part of the light field only
    for (const vec3& p : points) {
      const auto q = project(cam, p);
      ASSERT_TRUE(q.has_value());
      EXPECT_GE(q->pixel.x, 1.0f);
      EXPECT_GE(q->pixel.y, 1.0f);
      EXPECT_LE(q->pixel.x, float(cam.width) - 1.0f);
      EXPECT_LE(q->pixel.y, float(cam.height) - 1.0f);
      EXPECT_LT(q->depth, cam.far);
    }
  }
}

// Fitting the maps to the receivers moves the texel grid only: the answers stay those of
// whole-field maps of the same density but for edge texels, and as close to the rays.
TEST(SoftShadows, FittedMapsAnswerAsWholeFieldMaps) {
  LightSetup s(0.3f, 4, 64);
  const RayScene rays(s.scene);
  ShadowMapOptions full, fitted;
  full.resolution = fitted.resolution = 256;
  full.fit_receivers = false;
  ShadowMapStats st_full, st_fitted;
  const LightVisibility a = shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, full, nullptr, &st_full);
  const LightVisibility b = shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, fitted, nullptr, &st_fitted);
  const LightVisibility exact = ray_visibility(rays, s.scene, s.receivers, s.samples);
  EXPECT_EQ(st_fitted.receivers_outside, 0u);
  EXPECT_LT(st_fitted.texels, st_full.texels);
  EXPECT_FLOAT_EQ(st_fitted.focal_px, st_full.focal_px);
  EXPECT_LT(compare_visibility(b, a, s.receivers).visibility_mean, 1.0);
  EXPECT_LT(compare_visibility(b, exact, s.receivers).visibility_mean, 4.0);  // the whole-field maps' bound
}

// A footprint density lowers the focal length to about that many texels per receiver
// spacing, and no further than `resolution` allows.
TEST(SoftShadows, FootprintTexelsSetTheDensity) {
  LightSetup s(0.3f, 4, 64);
  ShadowMapOptions o;
  o.resolution = 4096;
  ShadowMapStats dense, coarse, capped;
  shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, o, nullptr, &dense);
  o.footprint_texels = 2.0f;
  shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, o, nullptr, &coarse);
  EXPECT_LT(coarse.focal_px, 0.5f * dense.focal_px);
  EXPECT_LT(coarse.texels, dense.texels / 4);
  o.resolution = 16;
  shadow_map_visibility(s.scene, s.receivers, s.samples, s.cams, o, nullptr, &capped);
  EXPECT_LT(capped.focal_px, coarse.focal_px);
}

// Drawing each map in one task with the depth-only rasterizer gives the same maps as the
// tiled rasterizer, so the same answers, for fitted and whole-field maps, on the geometry
// and on a reconstruction (clipped and sliver triangles), for any thread count.
TEST(SoftShadows, PerMapTasksAnswerAsTheTiledRasterizer) {
  LightSetup s(0.5f, 4, 64);
  OccluderOptions o;
  o.resolution = 128;
  const Occluders occ = build_occluders(s.scene, nullptr, s.light, s.cams, ShadowSampling::Nrr, o);
  for (const Scene* scene : {static_cast<const Scene*>(&s.scene), &occ.scene})
    for (bool fit : {true, false}) {
      ShadowMapOptions tiled, tasks;
      tiled.resolution = tasks.resolution = 256;
      tiled.fit_receivers = tasks.fit_receivers = fit;
      tiled.per_map_tasks = false;
      tasks.read_texels_only = false;
      ShadowMapStats st_tiled, st_tasks;
      const LightVisibility a = shadow_map_visibility(*scene, s.receivers, s.samples, s.cams, tiled, nullptr, &st_tiled);
      LightVisibility b, c;
      {
        ThreadLimit one(1);
        b = shadow_map_visibility(*scene, s.receivers, s.samples, s.cams, tasks, nullptr, &st_tasks);
      }
      {
        ThreadLimit two(2);
        c = shadow_map_visibility(*scene, s.receivers, s.samples, s.cams, tasks);
      }
      EXPECT_EQ(a.bits, b.bits) << fit;
      EXPECT_EQ(b.bits, c.bits) << fit;
      EXPECT_EQ(st_tiled.triangles_drawn, st_tasks.triangles_drawn) << fit;
      EXPECT_GT(st_tasks.triangles_drawn, 0u);
    }
}

// Culling the triangles that cover no texel a receiver reads keeps every answer, on the
// geometry and on a reconstruction (clipped and sliver triangles), and sets up fewer
// triangles in maps of the same size.
TEST(SoftShadows, ReadTexelsOnlyKeepsTheAnswers) {
  LightSetup s(0.5f, 4, 64);
  OccluderOptions oo;
  oo.resolution = 128;
  const Occluders occ = build_occluders(s.scene, nullptr, s.light, s.cams, ShadowSampling::Nrr, oo);
  for (const Scene* scene : {static_cast<const Scene*>(&s.scene), &occ.scene}) {
    ShadowMapOptions all, read;
    all.resolution = read.resolution = 256;
    all.read_texels_only = false;
    ShadowMapStats st_all, st_read;
    const LightVisibility a = shadow_map_visibility(*scene, s.receivers, s.samples, s.cams, all, nullptr, &st_all);
    const LightVisibility b = shadow_map_visibility(*scene, s.receivers, s.samples, s.cams, read, nullptr, &st_read);
    EXPECT_EQ(a.bits, b.bits);
    EXPECT_LT(st_read.triangles_drawn, st_all.triangles_drawn);
    EXPECT_EQ(st_read.texels, st_all.texels);
  }
}

TEST(SoftShadows, ParsesSamplingNames) {
  EXPECT_EQ(parse_shadow_sampling("nrr", "--sampling"), ShadowSampling::Nrr);
  EXPECT_EQ(parse_shadow_sampling("peeling", "--sampling"), ShadowSampling::Peeling);
  EXPECT_THROW(parse_shadow_sampling("nrr-pixel", "--sampling"), InputError);
  EXPECT_THROW(parse_reconstruction("points", "--reconstruction"), InputError);
}

}  // namespace
}  // namespace proxima
