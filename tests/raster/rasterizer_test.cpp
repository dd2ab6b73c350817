// Rasterizer: watertightness (coverage counts through the fragment test), known answers,
// clipping, culling, determinism across thread counts, degenerate and empty inputs.
#include "proxima/raster/rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/scene/builtin_scenes.h"

namespace proxima {
namespace {

// Regular n × n grid of quads in the plane z = z0 spanning [−half, half]², counter-
// clockwise seen from +z; interior vertices jittered by up to `jitter` of a cell.
Mesh grid_mesh(int n, float half, float z0, float jitter, uint64_t seed) {
  Mesh m;
  Pcg32 rng(seed);
  const float cell = 2.0f * half / float(n);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      vec3 p(-half + cell * float(i), -half + cell * float(j), z0);
      if (i > 0 && i < n && j > 0 && j < n) {
        p.x += (rng.next_float() - 0.5f) * jitter * cell;
        p.y += (rng.next_float() - 0.5f) * jitter * cell;
      }
      m.positions.push_back(p);
    }
  auto at = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Alternate the diagonal so both edge directions occur.
      if ((i + j) % 2) {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        m.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  return m;
}

// UV sphere, outward counter-clockwise triangles, poles as single vertices.
Mesh sphere_mesh(vec3 center, float radius, int segments, int rings) {
  Mesh m;
  m.positions.push_back(center + vec3(0, radius, 0));
  for (int r = 1; r < rings; ++r) {
    const float theta = kPi * float(r) / float(rings);
    for (int s = 0; s < segments; ++s) {
      const float phi = 2.0f * kPi * float(s) / float(segments);
      m.positions.push_back(center + radius * vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                   -std::sin(theta) * std::sin(phi)));
    }
  }
  m.positions.push_back(center - vec3(0, radius, 0));
  const uint32_t south = uint32_t(m.positions.size() - 1);
  auto ring = [&](int r, int s) { return uint32_t(1 + (r - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) m.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.triangles.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      m.triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  for (int s = 0; s < segments; ++s)
    m.triangles.push_back({south, ring(rings - 1, s + 1), ring(rings - 1, s)});
  return m;
}

Scene scene_of(const std::vector<Mesh>& meshes) {
  Scene scene;
  const uint32_t mat = add_material(scene, Material{});
  for (size_t i = 0; i < meshes.size(); ++i) add_object(scene, meshes[i], "mesh" + std::to_string(i), mat);
  return scene;
}

// Per-pixel count of covered fragments (depth test off, every fragment counted).
ImageU32 coverage(const Scene& scene, const Camera& camera, CullMode cull) {
  ImageU32 count(camera.width, camera.height, 1, 0u);
  RasterOptions options;
  options.depth_test = false;
  options.cull = cull;
  RasterImages out;
  rasterize(scene, camera, options, out, [&](const Fragment& f) {
    ++count.at(f.x, f.y);
    return true;
  });
  return count;
}

TEST(Rasterizer, GridCoversEveryPixelCenterExactlyOnce) {
  // 96×96 quads = 18432 triangles, jittered, seen obliquely so edges take all slopes; the
  // camera is placed so many vertices land exactly on pixel centers and edges.
  const Scene scene = scene_of({grid_mesh(96, 10.0f, 0.0f, 0.6f, 7)});
  for (const Camera& camera :
       {look_at(vec3(0, 0, 5), vec3(0, 0, 0), vec3(0, 1, 0), 60.0f, 256, 192),
        look_at(vec3(0.3f, -0.7f, 3), vec3(0.5f, 0.2f, 0), vec3(0.2f, 1, 0), 75.0f, 301, 257)}) {
    const ImageU32 count = coverage(scene, camera, CullMode::None);
    size_t bad = 0;
    for (uint32_t c : count.data()) bad += c != 1;
    EXPECT_EQ(bad, 0u);
  }
}

TEST(Rasterizer, AxisAlignedGridOnPixelCentersIsWatertight) {
  // Grid vertices exactly on pixel centers and pixel corners: every tie goes through the
  // fill rule.
  const int w = 128, h = 128;
  const Camera camera = look_at(vec3(0, 0, 1), vec3(0, 0, 0), vec3(0, 1, 0), 90.0f, w, h);
  // At z = 0 (depth 1) with 90° fov one pixel is 2/128 wide; 64 cells of 2 pixels shifted
  // by half a pixel put vertices on pixel centers.
  Mesh m = grid_mesh(66, 66.0f / 64.0f, 0.0f, 0.0f, 1);
  for (vec3& p : m.positions) p += vec3(1.0f / 128.0f, 1.0f / 128.0f, 0.0f);
  const ImageU32 count = coverage(scene_of({m}), camera, CullMode::None);
  size_t bad = 0;
  for (uint32_t c : count.data()) bad += c != 1;
  EXPECT_EQ(bad, 0u);
}

TEST(Rasterizer, ClosedSphereWithBackFaceCullingCoversSilhouetteOnce) {
  const vec3 center(0.2f, -0.1f, 0.0f);
  const float radius = 1.0f;
  const Scene scene = scene_of({sphere_mesh(center, radius, 96, 64)});
  const Camera camera = look_at(vec3(0.5f, 0.8f, 3.2f), center, vec3(0, 1, 0), 50.0f, 256, 256);
  const ImageU32 culled = coverage(scene, camera, CullMode::Back);
  const ImageU32 both = coverage(scene, camera, CullMode::None);
  size_t inside = 0, bad = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = ray_through(camera, vec2(x + 0.5f, y + 0.5f));
      // Distance of the pixel ray from the center; well inside the (inscribed) mesh's
      // silhouette below 0.99 r.
      const vec3 oc = center - ray.origin;
      const float dist = glm::length(oc - glm::dot(oc, ray.dir) * ray.dir);
      const uint32_t c1 = culled.at(x, y), c2 = both.at(x, y);
      if (dist < 0.99f * radius) {
        ++inside;
        bad += c1 != 1 || c2 != 2;
      } else {
        bad += c1 > 1 || c2 != 2 * c1;
      }
    }
  EXPECT_GT(inside, 10000u);
  EXPECT_EQ(bad, 0u);
}

TEST(Rasterizer, KnownDepthAndBarycentricsOnAQuad) {
  // A quad facing the camera at distance 4: depth 4 everywhere it covers, and the
  // barycentrics reproduce the world point of the pixel ray.
  Mesh m;
  m.positions = {{-1, -1, -4}, {1, -1, -4}, {1, 1, -4}, {-1, 1, -4}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Scene scene = scene_of({m});
  const Camera camera = look_at(vec3(0, 0, 0), vec3(0, 0, -1), vec3(0, 1, 0), 20.0f, 64, 64);
  RasterOptions options;
  options.outputs = kRasterGBuffer;
  const RasterImages img = rasterize(scene, camera, options);
  size_t covered = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const uint32_t t = img.triangle.at(x, y);
      if (t == kNoTriangle) {
        EXPECT_EQ(img.depth.at(x, y), kInf);
        EXPECT_EQ(img.object.at(x, y), kNoObject);
        continue;
      }
      ++covered;
      EXPECT_NEAR(img.depth.at(x, y), 4.0f, 1e-5f);
      EXPECT_EQ(img.object.at(x, y), 0u);
      const vec3 p = triangle_point(scene, t, img.barycentric.at(x, y, 0), img.barycentric.at(x, y, 1));
      const vec3 expected = unproject(camera, vec2(x + 0.5f, y + 0.5f), 4.0f);
      EXPECT_NEAR(glm::distance(p, expected), 0.0f, 1e-4f);
      EXPECT_NEAR(img.normal.at(x, y, 2), 1.0f, 1e-5f);
      EXPECT_NEAR(img.diffuse.at(x, y, 0), 0.8f, 1e-6f);
    }
  EXPECT_EQ(covered, 64u * 64u);  // the quad fills the 20° view at distance 4
}

TEST(Rasterizer, DirectLightIsUnshadowedLambert) {
  // Quad at distance 4 facing the camera, point light 2 m in front of its center: the
  // pixel at the center receives I·cos 0/r² = I/4, diffuse radiance albedo/π·I/4.
  Mesh m;
  m.positions = {{-1, -1, -4}, {1, -1, -4}, {1, 1, -4}, {-1, 1, -4}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  Scene scene = scene_of({m});
  scene.point_lights.push_back({vec3(0, 0, -2), vec3(8.0f)});
  const Camera camera = look_at(vec3(0, 0, 0), vec3(0, 0, -1), vec3(0, 1, 0), 20.0f, 64, 64);
  RasterOptions options;
  options.outputs = kRasterDiffuse;
  options.direct_light = true;
  const RasterImages img = rasterize(scene, camera, options);
  EXPECT_NEAR(img.diffuse.at(32, 32, 1), 0.8f / kPi * 2.0f, 2e-3f);
}

TEST(Rasterizer, PerspectiveCorrectOnASlantedPlane) {
  // A floor seen at a grazing angle: depth and barycentrics agree with the ray/plane
  // intersection (perspective-correct interpolation), not with screen-linear ones.
  Mesh m;
  m.positions = {{-50, 0, 0}, {50, 0, 0}, {50, 0, -100}, {-50, 0, -100}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Scene scene = scene_of({m});
  const Camera camera = look_at(vec3(0, 1, 0), vec3(0, 0.8f, -10), vec3(0, 1, 0), 60.0f, 128, 128);
  RasterOptions options;
  options.outputs = kRasterDepthId | kRasterBarycentric;
  const RasterImages img = rasterize(scene, camera, options);
  size_t checked = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const uint32_t t = img.triangle.at(x, y);
      if (t == kNoTriangle) continue;
      const Ray ray = ray_through(camera, vec2(x + 0.5f, y + 0.5f));
      const float hit_t = -ray.origin.y / ray.dir.y;
      const vec3 hit = ray.origin + hit_t * ray.dir;
      const float depth = glm::dot(hit - camera.position, camera_forward(camera));
      // Snapping moves vertices by up to 1/8192 pixel, which at a grazing angle moves the
      // plane by ∂depth/∂pixel / 8192 ≈ depth² / (8192 f): small below depth 20.
      if (depth > 20.0f) continue;
      EXPECT_NEAR(img.depth.at(x, y), depth, 1e-4f * depth);
      const vec3 p = triangle_point(scene, t, img.barycentric.at(x, y, 0), img.barycentric.at(x, y, 1));
      EXPECT_NEAR(glm::distance(p, hit), 0.0f, 1e-4f * depth);
      ++checked;
    }
  EXPECT_GT(checked, 3000u);
}

TEST(Rasterizer, NearerTriangleWinsAndTiesGoToLowerId) {
  Mesh a, b;
  a.positions = {{-1, -1, -3}, {1, -1, -3}, {0, 1, -3}};
  a.triangles = {{0, 1, 2}};
  b = a;
  Mesh c = a;
  for (vec3& p : c.positions) p.z = -2;  // in front
  const Camera camera = look_at(vec3(0, 0, 0), vec3(0, 0, -1), vec3(0, 1, 0), 60.0f, 32, 32);
  // Coplanar duplicates 0 and 1: 0 wins wherever drawn, in either draw order.
  const Scene ties = scene_of({a, b});
  for (std::vector<uint32_t> order : {std::vector<uint32_t>{0, 1}, std::vector<uint32_t>{1, 0}}) {
    RasterOptions options;
    options.objects = order;
    const RasterImages img = rasterize(ties, camera, options);
    for (uint32_t t : img.triangle.data()) EXPECT_TRUE(t == 0 || t == kNoTriangle);
  }
  const Scene front = scene_of({a, c});
  const RasterImages img = rasterize(front, camera);
  EXPECT_EQ(img.triangle.at(16, 16), 1u);
  EXPECT_NEAR(img.depth.at(16, 16), 2.0f, 1e-6f);
}

TEST(Rasterizer, NearPlaneClippingKeepsTheVisiblePart) {
  // A floor 3 cm below the eye runs under and behind the camera, which looks 45° down:
  // triangles cross the near plane (5 cm) and all four sides. Every pixel whose ray hits
  // the floor must see it at the ray/plane depth; every other pixel stays empty.
  Mesh m = grid_mesh(8, 100.0f, 0.0f, 0.0f, 3);
  for (vec3& p : m.positions) p = vec3(p.x, -1.0f, p.y);
  const Scene scene = scene_of({m});
  const Camera camera =
      look_at(vec3(0, -0.97f, 0), vec3(0.1f, -1.97f, -1), vec3(0, 1, 0), 90.0f, 96, 96, 0.05f, 1000.0f);
  RasterStats stats;
  const RasterImages img = rasterize(scene, camera, {}, &stats);
  EXPECT_GT(stats.triangles_clipped, 0u);
  auto ray_depth = [&](float px, float py) {
    const Ray ray = ray_through(camera, vec2(px, py));
    const float t = ray.dir.y < 0.0f ? -0.03f / ray.dir.y : kInf;
    const vec3 hit = ray.origin + t * ray.dir;
    const bool on_floor = t < kInf && std::abs(hit.x) < 99.0f && std::abs(hit.z) < 99.0f;
    return on_floor ? t * glm::dot(ray.dir, camera_forward(camera)) : kInf;
  };
  size_t near_clipped = 0;
  size_t checked = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      const float depth = ray_depth(x + 0.5f, y + 0.5f);
      if (depth == kInf) continue;         // off the floor (borders: ties with the floor's edge)
      if (depth < camera.near * 1.001f) {  // in front of the near plane: clipped away
        if (depth < camera.near * 0.999f) {
          EXPECT_EQ(img.triangle.at(x, y), kNoTriangle) << x << "," << y;
          ++near_clipped;
        }
        continue;
      }
      ASSERT_NE(img.triangle.at(x, y), kNoTriangle) << x << "," << y;
      // Snapping moves vertices by ≤ 1/8192 pixel in x and in y: allow the depth change
      // over 1/1024 pixel along each axis (the forward difference underestimates the slope
      // where depth grows hyperbolically towards the horizon).
      const float slope =
          std::abs(ray_depth(x + 0.5f, y + 1.5f) - depth) + std::abs(ray_depth(x + 1.5f, y + 0.5f) - depth);
      if (slope == kInf) continue;
      EXPECT_NEAR(img.depth.at(x, y), depth, 1e-4f * depth + slope / 1024.0f) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 3000u);
  EXPECT_GT(near_clipped, 0u);
}

TEST(Rasterizer, TriangleBehindCameraOrBeyondFarDrawsNothing) {
  Mesh m;
  m.positions = {{-1, -1, 3}, {1, -1, 3}, {0, 1, 3}, {-1, -1, -30}, {1, -1, -30}, {0, 1, -30}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  const Camera camera = look_at(vec3(0), vec3(0, 0, -1), vec3(0, 1, 0), 60.0f, 32, 32, 0.1f, 20.0f);
  RasterStats stats;
  const RasterImages img = rasterize(scene_of({m}), camera, {}, &stats);
  for (uint32_t t : img.triangle.data()) EXPECT_EQ(t, kNoTriangle);
  EXPECT_EQ(stats.triangles_rasterized, 0u);
}

TEST(Rasterizer, ObjectsOutsideTheFrustumAreCulled) {
  Mesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  Mesh behind = m, visible = m;
  for (vec3& p : behind.positions) p.z += 10;
  for (vec3& p : visible.positions) p.z -= 10;
  const Camera camera = look_at(vec3(0), vec3(0, 0, -1), vec3(0, 1, 0), 60.0f, 32, 32);
  RasterStats stats;
  rasterize(scene_of({behind, visible}), camera, {}, &stats);
  EXPECT_EQ(stats.objects_culled, 1u);
  EXPECT_EQ(stats.objects_drawn, 1u);
  EXPECT_EQ(stats.triangles_submitted, 1u);
}

// With a triangle id list an object is culled (and counted) once, not once per triangle.
TEST(Rasterizer, IdListCountsACulledObjectOnce) {
  const Mesh behind = grid_mesh(4, 1.0f, 3.0f, 0.0f, 1);  // behind the camera, 32 triangles
  const Mesh visible = grid_mesh(4, 1.0f, -3.0f, 0.0f, 1);
  const Scene scene = scene_of({behind, visible});
  const Camera camera = look_at(vec3(0), vec3(0, 0, -1), vec3(0, 1, 0), 60.0f, 64, 64);
  std::vector<uint32_t> all(scene.triangles.size());
  for (size_t t = 0; t < all.size(); ++t) all[t] = uint32_t(t);
  RasterOptions options;
  options.triangles = all;
  RasterImages img;
  const RasterStats stats = rasterize(scene, camera, options, img, AcceptAllFragments{});
  EXPECT_EQ(stats.objects_culled, 1u);
  EXPECT_EQ(stats.objects_drawn, 1u);
  EXPECT_EQ(stats.triangles_submitted, all.size() / 2);
  size_t covered = 0;
  for (uint32_t t : img.triangle.data()) covered += t != kNoTriangle;
  EXPECT_GT(covered, 0u);
}

TEST(Rasterizer, DegenerateAndEmptyInputsDrawNothing) {
  Mesh m;
  m.positions = {{0, 0, -2}, {1, 0, -2}, {2, 0, -2}, {0, 0, -2}};
  m.triangles = {{0, 1, 2}, {0, 3, 1}};  // collinear; two equal vertices
  const Camera camera = look_at(vec3(0), vec3(0, 0, -1), vec3(0, 1, 0), 60.0f, 16, 16);
  for (const Scene& scene : {scene_of({m}), Scene{}}) {
    RasterOptions options;
    options.outputs = kRasterGBuffer;
    const RasterImages img = rasterize(scene, camera, options);
    for (uint32_t t : img.triangle.data()) EXPECT_EQ(t, kNoTriangle);
    for (float d : img.depth.data()) EXPECT_EQ(d, kInf);
  }
}

TEST(Rasterizer, NonFiniteVerticesDropTheirTrianglesOnly) {
  Mesh m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  m.positions = {{-1, -1, -3}, {1, -1, -3}, {0, 1, -3}, {nan, 0, -3}, {kInf, 0, -3}, {0, -kInf, -3}};
  m.triangles = {{0, 1, 3}, {0, 4, 2}, {5, 1, 2}, {0, 1, 2}};
  Scene scene;
  const uint32_t mat = add_material(scene, Material{});
  add_object(scene, m, "m", mat);  // unsanitized on purpose
  const Camera camera = look_at(vec3(0), vec3(0, 0, -1), vec3(0, 1, 0), 60.0f, 32, 32);
  RasterStats stats;
  const RasterImages img = rasterize(scene, camera, {}, &stats);
  for (uint32_t t : img.triangle.data()) EXPECT_TRUE(t == 3 || t == kNoTriangle);
  EXPECT_EQ(img.triangle.at(16, 16), 3u);
  EXPECT_EQ(stats.triangles_culled, 3u);
}

TEST(Rasterizer, TriangleSubsetDrawsOnlyThoseTriangles) {
  const Scene scene = scene_of({grid_mesh(4, 1.0f, -3.0f, 0.0f, 1)});
  const Camera camera = look_at(vec3(0), vec3(0, 0, -1), vec3(0, 1, 0), 60.0f, 64, 64);
  const std::vector<uint32_t> subset = {3, 17, 30};
  RasterOptions options;
  options.triangles = subset;
  const RasterImages img = rasterize(scene, camera, options);
  size_t covered = 0;
  for (uint32_t t : img.triangle.data()) {
    EXPECT_TRUE(t == kNoTriangle || t == 3 || t == 17 || t == 30);
    covered += t != kNoTriangle;
  }
  EXPECT_GT(covered, 0u);
}

TEST(Rasterizer, InvalidCameraThrowsInputError) {
  Camera camera;
  camera.width = 0;
  EXPECT_THROW(rasterize(Scene{}, camera), InputError);
}

TEST(Rasterizer, OneAndTwoThreadsAreBitIdentical) {
  std::vector<Mesh> meshes;
  for (int i = 0; i < 6; ++i)
    meshes.push_back(
        sphere_mesh(vec3(float(i % 3) - 1.0f, float(i / 3) - 0.5f, -float(i) * 0.3f), 0.7f, 64, 32));
  meshes.push_back(grid_mesh(64, 5.0f, -2.0f, 0.5f, 11));
  const Scene scene = scene_of(meshes);
  const Camera camera = look_at(vec3(0.2f, 0.3f, 4.0f), vec3(0), vec3(0, 1, 0), 60.0f, 300, 200);
  RasterOptions options;
  options.outputs = kRasterGBuffer;
  RasterImages one, two;
  {
    ThreadLimit limit(1);
    one = rasterize(scene, camera, options);
  }
  {
    ThreadLimit limit(2);
    two = rasterize(scene, camera, options);
  }
  EXPECT_TRUE(one.depth == two.depth);
  EXPECT_TRUE(one.triangle == two.triangle);
  EXPECT_TRUE(one.barycentric == two.barycentric);
  EXPECT_TRUE(one.normal == two.normal);
  EXPECT_TRUE(one.diffuse == two.diffuse);
  EXPECT_TRUE(one.object == two.object);
}

// Four overlapping spheres over a jittered grid (seen from (0.2, 0.3, 4)).
Scene spheres_over_grid() {
  std::vector<Mesh> meshes;
  for (int i = 0; i < 4; ++i) meshes.push_back(sphere_mesh(vec3(float(i) * 0.4f - 0.6f, 0.0f, -float(i) * 0.3f), 0.8f, 48, 24));
  meshes.push_back(grid_mesh(48, 5.0f, -2.0f, 0.5f, 7));
  return scene_of(meshes);
}

// A test with keep_run (one call per row run) must give what the per-fragment test gives:
// the same fragments tested, the same ones written. A keep/discard pattern hashed from
// the fragment, with and without UVs, over overlapping spheres and a jittered grid.
struct HashedKeep {
  static bool keep(const Fragment& f) {
    const uint32_t h = (uint32_t(f.x) * 73856093u) ^ (uint32_t(f.y) * 19349663u) ^ (f.triangle * 83492791u);
    return (h >> 7) % 3 != 0;
  }
  bool operator()(const Fragment& f) const { return keep(f); }
};
struct HashedKeepRuns : HashedKeep {
  mutable uint64_t runs = 0;
  uint64_t keep_run(const Fragment* f, int n) const {
    ++runs;
    uint64_t bits = 0;
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(f[k].y, f[0].y);
      EXPECT_EQ(f[k].triangle, f[0].triangle);
      if (k > 0) {
        EXPECT_GT(f[k].x, f[k - 1].x);
      }
      if (keep(f[k])) bits |= uint64_t(1) << k;
    }
    return bits;
  }
};

TEST(Rasterizer, RunTestGivesThePerFragmentResult) {
  const Scene scene = spheres_over_grid();
  const Camera camera = look_at(vec3(0.2f, 0.3f, 4.0f), vec3(0), vec3(0, 1, 0), 60.0f, 200, 150);
  for (bool uv : {false, true}) {
    RasterOptions options;
    options.outputs = kRasterGBuffer;
    options.fragment_barycentrics = uv;
    RasterImages per_fragment, per_run;
    const RasterStats a = rasterize(scene, camera, options, per_fragment, HashedKeep{});
    HashedKeepRuns runs;
    const RasterStats b = rasterize(scene, camera, options, per_run, runs);
    EXPECT_GT(runs.runs, 1000u);
    EXPECT_EQ(a.fragments_tested, b.fragments_tested);
    EXPECT_EQ(a.fragments_written, b.fragments_written);
    EXPECT_LT(a.fragments_written, a.fragments_tested);  // the test does discard
    EXPECT_TRUE(per_fragment.depth == per_run.depth);
    EXPECT_TRUE(per_fragment.triangle == per_run.triangle);
    EXPECT_TRUE(per_fragment.barycentric == per_run.barycentric);
    EXPECT_TRUE(per_fragment.normal == per_run.normal);
  }
}

// keeps_all(t) lets the rasterizer keep a triangle's fragments without the test: the same
// images and counts as a test that answers true for them, and the test never sees them.
struct OddKept {
  static bool keep(const Fragment& f) { return (f.triangle & 1u) || HashedKeep::keep(f); }
  bool operator()(const Fragment& f) const { return keep(f); }
};
struct OddKeptHooked : OddKept {
  mutable uint64_t odd_seen = 0;
  bool keeps_all(uint32_t triangle) const { return triangle & 1u; }
  bool operator()(const Fragment& f) const {
    odd_seen += f.triangle & 1u;
    return keep(f);
  }
};
struct OddKeptHookedRuns : OddKeptHooked {
  uint64_t keep_run(const Fragment* f, int n) const {
    uint64_t bits = 0;
    for (int k = 0; k < n; ++k) {
      odd_seen += f[k].triangle & 1u;
      if (keep(f[k])) bits |= uint64_t(1) << k;
    }
    return bits;
  }
};

TEST(Rasterizer, KeepsAllHookGivesTheTestedResult) {
  const Scene scene = spheres_over_grid();
  const Camera camera = look_at(vec3(0.2f, 0.3f, 4.0f), vec3(0), vec3(0, 1, 0), 60.0f, 200, 150);
  RasterOptions options;
  options.outputs = kRasterGBuffer;
  RasterImages tested, hooked, hooked_runs;
  const RasterStats a = rasterize(scene, camera, options, tested, OddKept{});
  OddKeptHooked hook;
  const RasterStats b = rasterize(scene, camera, options, hooked, hook);
  OddKeptHookedRuns hook_runs;
  const RasterStats c = rasterize(scene, camera, options, hooked_runs, hook_runs);
  EXPECT_EQ(hook.odd_seen, 0u);
  EXPECT_EQ(hook_runs.odd_seen, 0u);
  EXPECT_LT(a.fragments_written, a.fragments_tested);  // the test does discard
  for (const RasterStats& s : {b, c}) {
    EXPECT_EQ(s.fragments_tested, a.fragments_tested);
    EXPECT_EQ(s.fragments_written, a.fragments_written);
  }
  for (const RasterImages* h : {&hooked, &hooked_runs}) {
    EXPECT_TRUE(h->depth == tested.depth);
    EXPECT_TRUE(h->triangle == tested.triangle);
    EXPECT_TRUE(h->barycentric == tested.barycentric);
    EXPECT_TRUE(h->diffuse == tested.diffuse);
  }
}

// Object ids without barycentrics, normals or diffuse: the tiles then hold no (u, v).
TEST(Rasterizer, ObjectIdsAloneFollowTheTriangleIds) {
  const Scene scene = make_builtin_scene("cornell");
  Camera cam = scene.cameras.at(0).camera;
  cam.width = 96;
  cam.height = 64;
  RasterOptions objects_only;
  objects_only.outputs = kRasterObject;
  const RasterImages a = rasterize(scene, cam, objects_only);
  const RasterImages b = rasterize(scene, cam);
  ASSERT_EQ(a.object.pixel_count(), b.triangle.pixel_count());
  size_t covered = 0;
  for (size_t i = 0; i < a.object.data().size(); ++i) {
    const uint32_t t = b.triangle.data()[i];
    covered += t != kNoTriangle;
    EXPECT_EQ(a.object.data()[i], t == kNoTriangle ? kNoObject : scene.triangle_object[t]) << i;
  }
  EXPECT_GT(covered, 0u);
}

}  // namespace
}  // namespace proxima
