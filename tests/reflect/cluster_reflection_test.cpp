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
TEST(ClusterReflection, OwnLayerAnswersRaysThatHitTheirOwnConcaveReflector) {
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
  ReflectionOptions opts;
  opts.supersample = 2;
  opts.glossy_rays = 8;
  const ReflectionFrame frame = prepare_reflection_frame(scene, eye, opts);
  ASSERT_GT(frame.sample_count(), 2000u);
  RayScene rays(scene);
  const TracedReflections traced = trace_reflections(scene, rays, frame);
  ClusterReflectionOptions without, with;
  without.own_layer = false;
  const ClusterReflections left_out = render_cluster_reflections(scene, frame, without, {}, &traced);
  const ClusterReflections own = render_cluster_reflections(scene, frame, with, {}, &traced);
  const uint64_t n = frame.sample_count();
  const uint64_t before = left_out.stats.occlusion_cause_samples[int(OcclusionCause::OwnReflector)];
  const uint64_t after = own.stats.occlusion_cause_samples[int(OcclusionCause::OwnReflector)];
  EXPECT_LT(left_out.stats.planar_clusters, left_out.stats.clusters);
  EXPECT_EQ(left_out.stats.own_layer_texels, 0u);
  EXPECT_GT(own.stats.own_layer_rays, 0u);
  EXPECT_GT(before * 5, n) << before << " of " << n;  // > 20% of the samples before
  EXPECT_LT(after * 4, before) << after << " vs " << before;
  const ImageU8 mask = reflective_pixel_mask(frame);
  const ImageF truth = compose_reflections(frame, traced.radiance);
  const double err_before = compare_images(compose_reflections(frame, left_out.radiance), truth, &mask).mae_avg;
  const double err_after = compare_images(compose_reflections(frame, own.radiance), truth, &mask).mae_avg;
  EXPECT_LT(err_after, err_before);
  std::cout << "own_curved_reflector samples " << before << " -> " << after << " of " << n << ", mae " << err_before
            << " -> " << err_after << "\n";
  std::vector<vec3> one;
  {
    ThreadLimit limit(1);
    one = render_cluster_reflections(scene, frame, with, {}, &traced).radiance;
  }
  EXPECT_TRUE(one == own.radiance);
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
  ReflectionOptions opts;
  opts.supersample = 2;
  opts.glossy_rays = 8;
  const ReflectionFrame frame = prepare_reflection_frame(scene, eye, opts);
  ASSERT_GT(frame.sample_count(), 2000u);
  RayScene rays(scene);
  const TracedReflections traced = trace_reflections(scene, rays, frame);
  ClusterReflectionOptions layer, exact;
  layer.own_exact = false;
  const ClusterReflections by_layer = render_cluster_reflections(scene, frame, layer, {}, &traced);
  const ClusterReflections by_exact = render_cluster_reflections(scene, frame, exact, {}, &traced);
  const uint64_t n = frame.sample_count();
  const uint64_t before = by_layer.stats.occlusion_cause_samples[int(OcclusionCause::OwnReflector)];
  const uint64_t after = by_exact.stats.occlusion_cause_samples[int(OcclusionCause::OwnReflector)];
  const ImageU8 mask = reflective_pixel_mask(frame);
  const ImageF truth = compose_reflections(frame, traced.radiance);
  const double err_before = compare_images(compose_reflections(frame, by_layer.radiance), truth, &mask).mae_avg;
  const double err_after = compare_images(compose_reflections(frame, by_exact.radiance), truth, &mask).mae_avg;
  std::cout << "own_curved_reflector samples " << before << " -> " << after << " of " << n << ", occlusion "
            << by_layer.stats.occlusion_error_samples << " -> " << by_exact.stats.occlusion_error_samples
            << ", mae " << err_before << " -> " << err_after << "\n";
  EXPECT_LT(by_exact.stats.planar_clusters, by_exact.stats.clusters);
  EXPECT_GT(by_exact.stats.own_layer_rays, 0u);
  EXPECT_GT(by_exact.stats.own_exact_triangles, 0u);
  EXPECT_EQ(by_exact.stats.own_layer_texels, 0u);
  // The own layer misses its own hits on a sizeable share of the samples; the exact test on
  // almost none.
  EXPECT_GT(before * 20, n) << before << " of " << n;
  EXPECT_LT(after * 100, n) << after << " of " << n;
  EXPECT_LT(err_after, err_before);
  std::vector<vec3> one;
  {
    ThreadLimit limit(1);
    one = render_cluster_reflections(scene, frame, exact, {}, &traced).radiance;
  }
  EXPECT_TRUE(one == by_exact.radiance);
}

}  // namespace proxima
