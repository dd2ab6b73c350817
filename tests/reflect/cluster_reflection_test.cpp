#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "proxima/core/parallel.h"
#include "proxima/eval/image_error.h"
#include "proxima/reflect/cluster_reflection.h"
#include "trace/test_geometry.h"
#include "reflect/wave_texture.h"

namespace proxima {

namespace {

// A 2 × 2 m mirror in the plane z = 0 facing +Z, a textured 8 × 8 m wall at z = 4 facing it,
// a point light between them.
Scene mirror_and_wall() {
  Scene s;
  s.name = "mirror-and-wall";
  const uint32_t wall_mat = add_waves_wall_material(s);
  const uint32_t mirror_mat = test::add_diffuse(s, vec3(0.9f), 1.0f, 0.0f);
  add_object(s, test::quad_mesh(vec3(-1, -1, 0), vec3(2, 0, 0), vec3(0, 2, 0)), "mirror", mirror_mat);
  add_object(s, test::quad_mesh(vec3(-4, -4, 4), vec3(0, 8, 0), vec3(8, 0, 0)), "wall", wall_mat);
  s.point_lights.push_back({vec3(0.0f, 0.5f, 3.0f), vec3(12.0f)});
  s.ambient = vec3(0.1f);
  return s;
}

const Camera kEye = look_at(vec3(0.4f, 0.3f, 2.5f), vec3(0.0f), vec3(0, 1, 0), 50.0f, 48, 48, 0.01f, 100.0f);

// Cluster reflections of `scene` from `eye` (2 × 2 samples, 8 lobe rays on glossy
// surfaces) with each option set of `variants`, against Embree on the same rays: per
// variant the output, its samples with an own-reflector occlusion error and its MAE over
// the reflective pixels; and whether the last variant gives the same bits on one thread.
struct OwnRun {
  ClusterReflections out;
  uint64_t own_errors = 0;
  double mae = 0.0;
};
struct OwnComparison {
  uint64_t samples = 0;
  std::vector<OwnRun> runs;
  bool last_same_on_one_thread = false;
};
OwnComparison compare_own_variants(const Scene& scene, const Camera& eye,
                                   const std::vector<ClusterReflectionOptions>& variants) {
  ReflectionOptions opts;
  opts.supersample = 2;
  opts.glossy_rays = 8;
  const ReflectionFrame frame = prepare_reflection_frame(scene, eye, opts);
  RayScene rays(scene);
  const TracedReflections traced = trace_reflections(scene, rays, frame);
  const ImageU8 mask = reflective_pixel_mask(frame);
  const ImageF truth = compose_reflections(frame, traced.radiance);
  OwnComparison c;
  c.samples = frame.sample_count();
  for (const ClusterReflectionOptions& o : variants) {
    OwnRun run;
    run.out = render_cluster_reflections(scene, frame, o, {}, &traced);
    run.own_errors = run.out.stats.occlusion_cause_samples[int(OcclusionCause::OwnReflector)];
    run.mae = compare_images(compose_reflections(frame, run.out.radiance), truth, &mask).mae_avg;
    c.runs.push_back(std::move(run));
  }
  ThreadLimit limit(1);
  c.last_same_on_one_thread =
      render_cluster_reflections(scene, frame, variants.back(), {}, &traced).radiance == c.runs.back().out.radiance;
  return c;
}

}  // namespace

TEST(ClusterReflection, PlanarMirrorReproducesTheTracedReflection) {
  const Scene scene = mirror_and_wall();
  ReflectionOptions opts;
  opts.supersample = 2;
  ReflectionFrame frame = prepare_reflection_frame(scene, kEye, opts);
  ASSERT_GT(frame.sample_count(), 1000u);
  RayScene rays(scene);
  TracedReflections traced = trace_reflections(scene, rays, frame);
  ClusterReflections cluster = render_cluster_reflections(scene, frame, {}, {}, &traced);
  EXPECT_EQ(cluster.stats.clusters, 1u);
  EXPECT_EQ(cluster.stats.planar_clusters, 1u);
  EXPECT_EQ(cluster.stats.env_fallback_samples, 0u);
  EXPECT_EQ(cluster.stats.occlusion_error_samples, 0u);
  EXPECT_EQ(cluster.stats.second_layer_texels, 0u);  // every ray passes through e0: one layer
  EXPECT_EQ(cluster.stats.own_layer_texels, 0u);     // a planar cluster's image holds its reflector
  const ImageU8 mask = reflective_pixel_mask(frame);
  const ImageError err =
      compare_images(compose_reflections(frame, cluster.radiance), compose_reflections(frame, traced.radiance), &mask);
  EXPECT_GT(err.pixels, 500u);
  for (int c = 0; c < 3; ++c) EXPECT_LT(err.mae[c], 1.0) << "channel " << c;
  // The reflection is not trivially dark: the wall shows up in it.
  float brightest = 0.0f;
  for (vec3 c : cluster.radiance) brightest = std::max(brightest, c.y);
  EXPECT_GT(brightest, 0.1f);
}

TEST(ClusterReflection, GlossyLobeIsIdenticalForAnyThreadCount) {
  Scene scene = mirror_and_wall();
  scene.materials[1].gloss = 0.4f;
  scene.materials[1].specular = 0.6f;
  ReflectionOptions opts;
  opts.supersample = 1;
  opts.glossy_rays = 9;
  std::vector<vec3> one, two;
  {
    ThreadLimit limit(1);
    ReflectionFrame frame = prepare_reflection_frame(scene, kEye, opts);
    EXPECT_EQ(frame.direction.size(), 9u * frame.sample_count());
    one = render_cluster_reflections(scene, frame, {}).radiance;
  }
  {
    ThreadLimit limit(2);
    two = render_cluster_reflections(scene, prepare_reflection_frame(scene, kEye, opts), {}).radiance;
  }
  ASSERT_EQ(one.size(), two.size());
  EXPECT_TRUE(one == two);
}

// A glossy mirror with a ball standing on it: lobe rays off the mirror direction pass
// behind the ball as seen from e0 and hit the wall there, absent from a single-layer image.
TEST(ClusterReflection, SecondLayerAnswersGlossyRaysHiddenBehindAnOccluder) {
  Scene scene = mirror_and_wall();
  scene.materials[1].gloss = 0.5f;
  scene.materials[1].specular = 0.8f;
  add_object(scene, test::sphere_mesh(vec3(0.0f, 0.0f, 0.45f), 0.4f, 16, 8), "ball",
             test::add_diffuse(scene, vec3(0.8f, 0.2f, 0.2f)));
  ReflectionOptions opts;
  opts.supersample = 1;
  opts.glossy_rays = 8;
  const ReflectionFrame frame = prepare_reflection_frame(scene, kEye, opts);
  RayScene rays(scene);
  const TracedReflections traced = trace_reflections(scene, rays, frame);
  ClusterReflectionOptions one, two;
  one.second_layer = false;
  const ClusterReflections single = render_cluster_reflections(scene, frame, one, {}, &traced);
  const ClusterReflections layered = render_cluster_reflections(scene, frame, two, {}, &traced);
  EXPECT_EQ(single.stats.second_layer_texels, 0u);
  EXPECT_GT(layered.stats.second_layer_texels, 0u);
  EXPECT_GT(layered.stats.second_layer_rays, 0u);
  ASSERT_GT(single.stats.occlusion_error_rays, 20u);
  EXPECT_LT(layered.stats.occlusion_error_rays * 4, single.stats.occlusion_error_rays);
  const ImageU8 mask = reflective_pixel_mask(frame);
  const ImageF truth = compose_reflections(frame, traced.radiance);
  const double err_single = compare_images(compose_reflections(frame, single.radiance), truth, &mask).mae_avg;
  const double err_layered = compare_images(compose_reflections(frame, layered.radiance), truth, &mask).mae_avg;
  EXPECT_LT(err_layered, err_single);
}

// A glossy L-shaped reflector, one object: a gently curved seat (a curved cluster) and a
// back standing at its edge. The seat's lobe rays hit the back and the back's hit the
// seat, i.e. their own reflector elsewhere, which a curved cluster's image leaves out.
TEST(ClusterReflection, OwnLayerAndExactTestAnswerRaysThatHitTheirOwnConcaveReflector) {
  Scene scene;
  scene.name = "glossy-l";
  const uint32_t mat = test::add_diffuse(scene, vec3(0.8f, 0.3f, 0.2f), 0.8f, 0.3f);
  Mesh seat;
  const int strips = 16;
  for (int i = 0; i <= strips; ++i) {
    const float x = -1.0f + 2.0f * float(i) / float(strips);
    const vec3 n = glm::normalize(vec3(-0.16f * x, 0.0f, 1.0f));  // of z = 0.08·x²
    for (float y : {-1.0f, 1.0f}) {
      seat.positions.push_back(vec3(x, y, 0.08f * x * x));
      seat.normals.push_back(n);
    }
  }
  for (uint32_t i = 0; i < uint32_t(strips); ++i) {
    const uint32_t a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
    seat.triangles.push_back(uvec3(a, c, d));
    seat.triangles.push_back(uvec3(a, d, b));
  }
  append_mesh(seat, test::quad_mesh(vec3(-1.0f, -1.0f, 0.0f), vec3(0.0f, 0.0f, 1.5f), vec3(2.0f, 0.0f, 0.0f)));
  add_object(scene, seat, "glossy-l", mat);
  scene.point_lights.push_back({vec3(0.3f, 1.0f, 2.5f), vec3(8.0f)});
  scene.ambient = vec3(0.1f);
  const Camera eye = look_at(vec3(0.2f, 1.6f, 1.6f), vec3(0.0f, -0.2f, 0.2f), vec3(0, 0, 1), 60.0f, 48, 48, 0.01f, 100.0f);
  ClusterReflectionOptions left_out, layer, exact;
  left_out.own_layer = false;
  layer.own_exact = false;
  const OwnComparison c = compare_own_variants(scene, eye, {left_out, layer, exact});
  ASSERT_GT(c.samples, 2000u);
  const OwnRun &none = c.runs[0], &by_layer = c.runs[1], &by_exact = c.runs[2];
  std::cout << "own_curved_reflector samples " << none.own_errors << " -> " << by_layer.own_errors << " (layer), "
            << by_exact.own_errors << " (exact) of " << c.samples << ", mae " << none.mae << " -> " << by_layer.mae
            << ", " << by_exact.mae << "\n";
  EXPECT_LT(none.out.stats.planar_clusters, none.out.stats.clusters);
  EXPECT_EQ(none.out.stats.own_layer_texels, 0u);
  EXPECT_GT(by_layer.out.stats.own_layer_texels, 0u);
  EXPECT_GT(by_layer.out.stats.own_layer_rays, 0u);
  EXPECT_GT(by_exact.out.stats.own_layer_rays, 0u);
  EXPECT_GT(none.own_errors * 5, c.samples) << none.own_errors << " of " << c.samples;  // > 20% before
  EXPECT_LT(by_layer.own_errors * 4, none.own_errors) << by_layer.own_errors << " vs " << none.own_errors;
  EXPECT_LE(by_exact.own_errors, by_layer.own_errors);
  EXPECT_LT(by_layer.mae, none.mae);
  EXPECT_LE(by_exact.mae, by_layer.mae);
  EXPECT_TRUE(c.last_same_on_one_thread);
}

// A (u, v) grid of `nu` × `nv` quads over surface(u, v) in [0, 1]², front towards
// normal(u, v) (each triangle wound so its face normal agrees with it).
template <class Surface, class Normal>
Mesh grid_mesh(int nu, int nv, Surface surface, Normal normal) {
  Mesh m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const float u = float(i) / float(nu), v = float(j) / float(nv);
      m.positions.push_back(surface(u, v));
      m.normals.push_back(glm::normalize(normal(u, v)));
    }
  auto at = [&](int i, int j) { return uint32_t(j * (nu + 1) + i); };
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    const vec3 face = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
    const vec3 want = m.normals[a] + m.normals[b] + m.normals[c];
    m.triangles.push_back(glm::dot(face, want) >= 0.0f ? uvec3(a, b, c) : uvec3(a, c, b));
  };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

// A glossy tub chair, one object: a round, gently dished seat, a half-cylinder back 0.6 m
// high around its rear half, and a slightly domed armrest top on that back. The seat's and
// the armrest top's points share a normal bin, so a curved cluster holds points 0.6 m
// apart along its normal that overlap in its camera's view; the seat's lobe rays hit the
// back, the back's hit the seat and the armrests.
TEST(ClusterReflection, OwnReflectorHitsAreRightWhereTheClusterOverlapsItself) {
  Scene scene;
  scene.name = "glossy-tub";
  const uint32_t mat = test::add_diffuse(scene, vec3(0.3f, 0.5f, 0.8f), 0.8f, 0.3f);
  const float pi = 3.14159265f, height = 0.6f;
  Mesh tub = grid_mesh(
      12, 32, [&](float u, float v) {
        const float r = u, a = 2.0f * pi * v;
        return vec3(r * std::cos(a), r * std::sin(a), 0.06f * r * r);
      },
      [&](float u, float v) {
        const float a = 2.0f * pi * v;
        return vec3(-0.12f * u * std::cos(a), -0.12f * u * std::sin(a), 1.0f);
      });
  append_mesh(tub, grid_mesh(
                       24, 8, [&](float u, float v) {
                         const float a = pi * u;
                         return vec3(1.02f * std::cos(a), 1.02f * std::sin(a), 0.06f + (height - 0.06f) * v);
                       },
                       [&](float u, float) { return vec3(-std::cos(pi * u), -std::sin(pi * u), 0.0f); }));
  append_mesh(tub, grid_mesh(
                       24, 4, [&](float u, float v) {
                         const float a = pi * u, r = 1.02f + 0.3f * v;
                         return vec3(r * std::cos(a), r * std::sin(a), height + 0.08f * v * (1.0f - v));
                       },
                       [&](float u, float v) {
                         const float a = pi * u, slope = 0.08f * (1.0f - 2.0f * v) / 0.3f;
                         return vec3(-slope * std::cos(a), -slope * std::sin(a), 1.0f);
                       }));
  add_object(scene, tub, "glossy-tub", mat);
  scene.point_lights.push_back({vec3(0.4f, -0.8f, 2.5f), vec3(8.0f)});
  scene.ambient = vec3(0.1f);
  const Camera eye = look_at(vec3(0.3f, -2.0f, 1.9f), vec3(0.0f, 0.2f, 0.2f), vec3(0, 0, 1), 60.0f, 48, 48, 0.01f, 100.0f);
  ClusterReflectionOptions layer, exact;
  layer.own_exact = false;
  const OwnComparison c = compare_own_variants(scene, eye, {layer, exact});
  ASSERT_GT(c.samples, 2000u);
  const OwnRun &by_layer = c.runs[0], &by_exact = c.runs[1];
  std::cout << "own_curved_reflector samples " << by_layer.own_errors << " -> " << by_exact.own_errors << " of "
            << c.samples << ", occlusion " << by_layer.out.stats.occlusion_error_samples << " -> "
            << by_exact.out.stats.occlusion_error_samples << ", mae " << by_layer.mae << " -> " << by_exact.mae
            << "\n";
  EXPECT_LT(by_exact.out.stats.planar_clusters, by_exact.out.stats.clusters);
  EXPECT_GT(by_exact.out.stats.own_layer_rays, 0u);
  EXPECT_GT(by_exact.out.stats.own_exact_triangles, 0u);
  EXPECT_EQ(by_exact.out.stats.own_layer_texels, 0u);
  // The own layer misses its own hits on a sizeable share of the samples; the exact test on
  // almost none.
  EXPECT_GT(by_layer.own_errors * 20, c.samples) << by_layer.own_errors << " of " << c.samples;
  EXPECT_LT(by_exact.own_errors * 100, c.samples) << by_exact.own_errors << " of " << c.samples;
  EXPECT_LT(by_exact.mae, by_layer.mae);
  EXPECT_TRUE(c.last_same_on_one_thread);
}

}  // namespace proxima
