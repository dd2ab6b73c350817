// Mesh reconstruction from depth images (thesis ch. 3, Algorithm 4): the hybrid mesh of a
// plane is watertight and covers exactly the plane's image, an isolated one-pixel object
// still gives a quad (the conventional mesh drops it), re-rendering reproduces the depth
// image (also with planar runs merged), and the result does not depend on the thread count.
#include "proxima/reconstruct/reconstruction.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/parallel.h"
#include "proxima/depthimage/sampling.h"
#include "proxima/scene/procedural.h"
#include "proxima/scene/sampling_scenes.h"

namespace proxima {
namespace {

Scene plane_scene() {
  Scene s;
  Material m;
  m.diffuse = vec3(0.5f);
  Mesh plane = make_plane(2.0f, 1.5f, 1, 1);  // y = 0, facing +y
  transform_mesh(plane, glm::rotate(mat4(1.0f), 0.3f, vec3(0, 0, 1)));
  add_object(s, plane, "plane", add_material(s, m));
  return s;
}

// Camera looking obliquely at the plane; its edges are inside the 64×48 image.
Camera plane_camera() { return look_at(vec3(0.4f, 2.0f, 2.2f), vec3(0.0f), vec3(0, 1, 0), 60.0f, 64, 48); }

Mesh hybrid_of(const Scene& scene, const Camera& cam, HybridStats* stats = nullptr) {
  const DepthImage i = render_depth_image(scene, cam, true);
  const DepthImage h = render_depth_image(scene, half_pixel_offset_camera(cam), true);
  return reconstruct_hybrid(i, h, stats);
}

ImageU32 ids_seen(const Mesh& mesh, const Camera& cam) {
  const Scene rec = reconstruction_scene(std::span<const Mesh>(&mesh, 1));
  RasterOptions o;
  o.outputs = kRasterDepthId;
  return rasterize(rec, cam, o).triangle;
}

TEST(Reconstruction, OffsetCameraPixelCentersArePixelCorners) {
  const Camera c = plane_camera();
  const Camera h = half_pixel_offset_camera(c);
  EXPECT_EQ(h.width, c.width + 1);
  EXPECT_EQ(h.height, c.height + 1);
  for (int j = 0; j <= c.height; j += 7)
    for (int i = 0; i <= c.width; i += 9) {
      const vec3 p = unproject(h, vec2(float(i) + 0.5f, float(j) + 0.5f), 3.0f);
      const auto q = project(c, p);
      ASSERT_TRUE(q.has_value());
      EXPECT_NEAR(q->pixel.x, float(i), 1e-3f);
      EXPECT_NEAR(q->pixel.y, float(j), 1e-3f);
    }
}

TEST(Reconstruction, HybridPlaneIsWatertightAndCoversItsImage) {
  const Scene scene = plane_scene();
  const Camera cam = plane_camera();
  const DepthImage image = render_depth_image(scene, cam, true);
  HybridStats stats;
  const Mesh mesh = hybrid_of(scene, cam, &stats);
  const size_t samples = sample_count(image);
  ASSERT_GT(samples, 300u);
  ASSERT_LT(samples, size_t(cam.width * cam.height));  // the plane's edges are in view
  EXPECT_EQ(mesh.triangles.size(), 2 * samples);
  EXPECT_EQ(stats.samples, samples);
  EXPECT_GT(stats.corners_fitted, 0u);  // the boundary corners: H misses the plane there

  // Every edge is used by one or two triangles; the ones used once are exactly the sides
  // of the sample region's pixel squares (a sample beside a non-sample or the border).
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const uvec3& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = t[e], b = t[(e + 1) % 3];
      uses[{std::min(a, b), std::max(a, b)}]++;
    }
  size_t boundary_edges = 0;
  for (const auto& [edge, n] : uses) {
    EXPECT_LE(n, 2) << "edge " << edge.first << "-" << edge.second;
    boundary_edges += n == 1;
  }
  size_t boundary_sides = 0;
  auto has = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < cam.width && y < cam.height && image.triangle.at(x, y) != kNoTriangle;
  };
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      if (has(x, y)) boundary_sides += !has(x - 1, y) + !has(x + 1, y) + !has(x, y - 1) + !has(x, y + 1);
  EXPECT_EQ(boundary_edges, boundary_sides);

  // Seen from the reference camera, the mesh covers exactly the plane's pixels.
  const ImageU32 seen = ids_seen(mesh, cam);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      EXPECT_EQ(seen.at(x, y) != kNoTriangle, has(x, y)) << x << "," << y;
}

// A square of half a pixel footprint in front of a far wall, centered on the ray through
// pixel (16, 12)'s center, so it covers that pixel center only.
Scene isolated_pixel_scene(const Camera& cam) {
  Scene s;
  Material m;
  m.diffuse = vec3(0.5f);
  const uint32_t mat = add_material(s, m);
  const float footprint = 2.0f / focal_length_px(cam);  // at depth 2
  Mesh dot = make_plane(0.5f * footprint, 0.5f * footprint, 1, 1);
  transform_mesh(dot, glm::rotate(mat4(1.0f), glm::radians(90.0f), vec3(1, 0, 0)));  // face +z
  transform_mesh(dot, glm::translate(mat4(1.0f), unproject(cam, vec2(16.5f, 12.5f), 2.0f)));
  add_object(s, dot, "dot", mat);
  Mesh wall = make_plane(20.0f, 20.0f, 1, 1);
  transform_mesh(wall, glm::rotate(mat4(1.0f), glm::radians(90.0f), vec3(1, 0, 0)));
  transform_mesh(wall, glm::translate(mat4(1.0f), vec3(0, 0, -5)));
  add_object(s, wall, "wall", mat);
  return s;
}

TEST(Reconstruction, IsolatedPixelGivesAQuadConventionalDropsIt) {
  const Camera cam = look_at(vec3(0.0f), vec3(0, 0, -1), vec3(0, 1, 0), 50.0f, 32, 24);
  const Scene scene = isolated_pixel_scene(cam);
  const DepthImage image = render_depth_image(scene, cam, true);
  ASSERT_NEAR(image.depth.at(16, 12), 2.0f, 1e-4f);
  size_t near_samples = 0;
  for (float d : image.depth.data()) near_samples += d < 3.0f;
  ASSERT_EQ(near_samples, 1u);  // the object is one pixel

  auto near_triangles = [](const Mesh& m) {
    size_t n = 0;
    for (const uvec3& t : m.triangles) {
      bool near = false;
      for (int k = 0; k < 3; ++k) near |= m.positions[t[k]].z > -3.0f;
      n += near;
    }
    return n;
  };
  const Mesh conventional = reconstruct_conventional(image);
  EXPECT_GT(conventional.triangles.size(), 0u);  // the wall is there
  EXPECT_EQ(near_triangles(conventional), 0u);   // the dot is not

  const Mesh hybrid = hybrid_of(scene, cam);
  EXPECT_EQ(near_triangles(hybrid), 2u);
  EXPECT_EQ(hybrid.triangles.size(), 2 * sample_count(image));
  // Its quad lies on the dot's plane (z = −2) and covers its pixel, nothing else.
  const ImageU32 seen = ids_seen(hybrid, cam);
  const Scene rec = reconstruction_scene(std::span<const Mesh>(&hybrid, 1));
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const uvec3 t = rec.triangles[seen.at(x, y)];
      const bool on_dot = rec.positions[t.x].z > -3.0f;
      EXPECT_EQ(on_dot, x == 16 && y == 12) << x << "," << y;
      if (on_dot) {
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(rec.positions[t[k]].z, -2.0f, 1e-4f);
      }
    }
}

// Fraction of the image's pixels whose re-rendered depth d' matches the image's depth d
// (both empty counts as a match): |d' − d| · |n·v| ≤ tolerance · d / f, with v the unit
// view ray and n the sample's normal — the re-rendered point lies within `tolerance` pixel
// footprints of the sample's tangent plane, the guarantee the continuity test gives the
// quad's corners (a plain depth bound would fail wherever a surface is seen edge-on).
double depth_match(const Mesh& mesh, const DepthImage& image, float tolerance) {
  const Scene rec = reconstruction_scene(std::span<const Mesh>(&mesh, 1));
  RasterOptions o;
  o.outputs = kRasterDepth;
  const ImageF depth = rasterize(rec, image.camera, o).depth;
  const float f = focal_length_px(image.camera);
  size_t ok = 0;
  for (int y = 0; y < image.depth.height(); ++y)
    for (int x = 0; x < image.depth.width(); ++x) {
      const float want = image.depth.at(x, y), got = depth.at(x, y);
      if (std::isinf(want)) {
        ok += std::isinf(got);
        continue;
      }
      const vec3 n(image.normal.at(x, y, 0), image.normal.at(x, y, 1), image.normal.at(x, y, 2));
      const vec3 v = ray_through(image.camera, vec2(float(x) + 0.5f, float(y) + 0.5f)).dir;
      // Depth → distance along the ray: divide by v·forward.
      const float along = std::abs(got - want) / glm::dot(v, camera_forward(image.camera));
      ok += along * std::abs(glm::dot(n, v)) <= tolerance * want / f;
    }
  return double(ok) / double(image.depth.pixel_count());
}

TEST(Reconstruction, HybridReproducesTheDepthImage) {
  for (const Scene& scene : {make_grass_scene(), make_nest_scene()}) {
    const Camera cam = look_at(scene.cameras[0].camera.position, vec3(0, 0.3f, 0), vec3(0, 1, 0),
                               scene.cameras[0].camera.vfov_deg, 128, 128, 0.05f, 100.0f);
    const DepthImage image = render_depth_image(scene, cam, true);
    const DepthImage offset = render_depth_image(scene, half_pixel_offset_camera(cam), true);
    const Mesh hybrid = reconstruct_hybrid(image, offset);
    EXPECT_GE(depth_match(hybrid, image, kContinuityTolerance), 0.99) << scene.name;
    // The conventional mesh leaves the fragments out, so it matches fewer pixels.
    EXPECT_LT(depth_match(reconstruct_conventional(image), image, kContinuityTolerance),
              depth_match(hybrid, image, kContinuityTolerance))
        << scene.name;
  }
}

TEST(Reconstruction, FragmentedNrrImageReproduced) {
  const Scene scene = make_grass_scene();
  const Camera base = look_at(scene.cameras[0].camera.position, vec3(0, 0.3f, 0), vec3(0, 1, 0), 50.0f, 96, 96);
  const Camera cams[2] = {base, look_at(base.position + vec3(0.6f, 0, 0), vec3(0, 0.3f, 0), vec3(0, 1, 0), 50.0f, 96, 96)};
  Camera offset_cams[2] = {half_pixel_offset_camera(cams[0]), half_pixel_offset_camera(cams[1])};
  const auto images = sample_nrr(scene, cams, Redundancy::Pixel, nullptr, true);
  const auto offsets = sample_nrr(scene, offset_cams, Redundancy::Pixel, nullptr, true);
  const Mesh hybrid = reconstruct_hybrid(images[1], offsets[1]);
  EXPECT_EQ(hybrid.triangles.size(), 2 * sample_count(images[1]));
  EXPECT_GE(depth_match(hybrid, images[1], kContinuityTolerance), 0.99);
}

TEST(Reconstruction, SameMeshForAnyThreadCount) {
  const Scene scene = make_grass_scene();
  const Camera cam = look_at(vec3(0, 1.4f, 3.2f), vec3(0, 0.1f, 0), vec3(0, 1, 0), 50.0f, 80, 64);
  const DepthImage image = render_depth_image(scene, cam, true);
  const DepthImage offset = render_depth_image(scene, half_pixel_offset_camera(cam), true);
  Mesh a, b, c, d, e, f;
  {
    ThreadLimit one(1);
    a = reconstruct_hybrid(image, offset);
    c = reconstruct_conventional(image);
    e = reconstruct_hybrid(image, offset, nullptr, true);
  }
  {
    ThreadLimit two(2);
    b = reconstruct_hybrid(image, offset);
    d = reconstruct_conventional(image);
    f = reconstruct_hybrid(image, offset, nullptr, true);
  }
  EXPECT_EQ(e.triangles, f.triangles);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(c.positions, d.positions);
  EXPECT_EQ(c.triangles, d.triangles);
}

// Merged planar runs: a plane's rows become one quad each, covering the same pixels at the
// same depths; on curved grass and the city's boxes the mesh re-renders as the unmerged one.
TEST(Reconstruction, MergedPlanarRunsKeepTheShape) {
  const Scene scene = plane_scene();
  const Camera cam = plane_camera();
  const DepthImage i = render_depth_image(scene, cam, true);
  const DepthImage h = render_depth_image(scene, half_pixel_offset_camera(cam), true);
  HybridStats stats;
  const Mesh merged = reconstruct_hybrid(i, h, &stats, true);
  EXPECT_EQ(stats.samples, sample_count(i));
  EXPECT_LE(stats.quads, size_t(cam.height));  // one run per row of the (convex) plane
  EXPECT_EQ(merged.triangles.size(), 2 * stats.quads);
  const Mesh plain = reconstruct_hybrid(i, h);
  const ImageU32 seen_merged = ids_seen(merged, cam), seen_plain = ids_seen(plain, cam);
  size_t covered_merged = 0, covered_plain = 0;
  for (uint32_t t : seen_merged.data()) covered_merged += t != kNoTriangle;
  for (uint32_t t : seen_plain.data()) covered_plain += t != kNoTriangle;
  EXPECT_EQ(covered_merged, covered_plain);
  for (size_t k = 0; k < seen_merged.data().size(); ++k)
    EXPECT_EQ(seen_merged.data()[k] == kNoTriangle, seen_plain.data()[k] == kNoTriangle) << k;
  EXPECT_GE(depth_match(merged, i, 0.01f), 0.999);
  for (const Scene& s : {make_grass_scene(), make_city_scene()}) {
    const Camera c = look_at(s.cameras[0].camera.position, vec3(0, 0.3f, 0), vec3(0, 1, 0),
                             s.cameras[0].camera.vfov_deg, 128, 128, 0.05f, 200.0f);
    const DepthImage si = render_depth_image(s, c, true);
    const DepthImage sh = render_depth_image(s, half_pixel_offset_camera(c), true);
    HybridStats st;
    const Mesh m = reconstruct_hybrid(si, sh, &st, true);
    EXPECT_LT(st.quads, st.samples) << s.name;
    EXPECT_GE(depth_match(m, si, kContinuityTolerance), depth_match(reconstruct_hybrid(si, sh), si, kContinuityTolerance) - 1e-3)
        << s.name;
  }
}

TEST(Reconstruction, EmptyImageGivesEmptyMesh) {
  Scene empty;
  const Camera cam = look_at(vec3(0, 0, 5), vec3(0), vec3(0, 1, 0), 50.0f, 16, 16);
  const DepthImage image = render_depth_image(empty, cam, true);
  const DepthImage offset = render_depth_image(empty, half_pixel_offset_camera(cam), true);
  EXPECT_TRUE(reconstruct_hybrid(image, offset).triangles.empty());
  EXPECT_TRUE(reconstruct_conventional(image).triangles.empty());
}

}  // namespace
}  // namespace proxima
