// Agreement with the Embree reference: on every built-in scene, from each of its cameras
// at 512×512, the rasterized triangle ids equal the ray-cast item buffer at ≥ 99.9% of
// pixel centers (a center on the edge two triangles share, or on two coincident surfaces —
// the level-* scenes' coplanar overlapping brushes — counts for either), and every
// disagreement is explained (a center on an edge, or two triangles within the depth epsilon). Plus near-plane/side clipping against Embree and
// the benchmark's bookkeeping.
#include "proxima/raster/raster_bench.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "proxima/scene/builtin_scenes.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima {
namespace {

IdAgreement agreement(const Scene& scene, const RayScene& rays, const Camera& camera) {
  const ItemBuffer reference = trace_item_buffer(scene, rays, camera);
  const RasterImages raster = rasterize(scene, camera);
  return compare_id_buffers(scene, camera, raster.triangle, reference.triangle);
}

TEST(RasterBench, BuiltinScenesAgreeWithEmbree) {
  for (const BuiltinSceneInfo& info : builtin_scenes()) {
    const Scene scene = make_builtin_scene(info.name);
    const RayScene rays(scene);
    ASSERT_FALSE(scene.cameras.empty()) << info.name;
    for (const NamedCamera& named : scene.cameras) {
      Camera camera = named.camera;
      camera.width = camera.height = 512;
      const IdAgreement a = agreement(scene, rays, camera);
      std::printf("[ agreement ] %s/%s: %.4f%% (%zu of %zu differ: %zu edge (%zu on a shared edge), %zu depth "
                  "(%zu coincident), %zu other)\n",
                  info.name.c_str(), named.name.c_str(), a.agreement_pct(), a.pixels - a.agree, a.pixels,
                  a.edge, a.on_shared_edge, a.depth, a.coincident, a.other);
      EXPECT_GE(a.agreement_with_ties_pct(), 99.9) << info.name << "/" << named.name;
      EXPECT_EQ(a.other, 0u) << info.name << "/" << named.name;
    }
  }
}

TEST(RasterBench, ClippingAgainstNearPlaneAndSidesAgreesWithEmbree) {
  // Cameras inside the Cornell box close to its walls and the block: walls cross the near
  // plane and every side of the view.
  const Scene scene = make_builtin_scene("cornell");
  const RayScene rays(scene);
  for (const Camera& camera :
       {look_at(vec3(0.95f, 0.05f, 0.9f), vec3(-1, 1.5f, -1), vec3(0, 1, 0), 100.0f, 256, 256, 0.02f),
        look_at(vec3(0.3f, 0.4f, -0.1f), vec3(0.45f, 0.5f, -0.35f), vec3(0, 1, 0), 90.0f, 256, 256, 0.05f),
        look_at(vec3(-0.9f, 1.95f, -0.9f), vec3(0, 0, 0.5f), vec3(0, 1, 0), 120.0f, 256, 256, 0.03f)}) {
    RasterStats stats;
    const ItemBuffer reference = trace_item_buffer(scene, rays, camera);
    const RasterImages raster = rasterize(scene, camera, {}, &stats);
    EXPECT_GT(stats.triangles_clipped, 0u);
    const IdAgreement a = compare_id_buffers(scene, camera, raster.triangle, reference.triangle);
    EXPECT_GE(a.agreement_pct(), 99.9);
    EXPECT_EQ(a.other, 0u);
    // Depth agrees wherever the ids do (both are −z_cam).
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x)
        if (raster.triangle.at(x, y) == reference.triangle.at(x, y) &&
            raster.triangle.at(x, y) != kNoTriangle) {
          EXPECT_NEAR(raster.depth.at(x, y), reference.depth.at(x, y), 1e-3f * reference.depth.at(x, y));
        }
  }
}

TEST(RasterBench, GBufferMatchesTheItemBuffer) {
  // Where the ids agree, normals and diffuse colors agree with the reference's.
  const Scene scene = make_builtin_scene("bathroom");
  const RayScene rays(scene);
  Camera camera = scene.cameras.front().camera;
  camera.width = camera.height = 128;
  const ItemBuffer reference = trace_item_buffer(scene, rays, camera);
  RasterOptions options;
  options.outputs = kRasterGBuffer;
  const RasterImages g = rasterize(scene, camera, options);
  size_t compared = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const uint32_t t = g.triangle.at(x, y);
      if (t == kNoTriangle || t != reference.triangle.at(x, y)) continue;
      ++compared;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.normal.at(x, y, c), reference.normal.at(x, y, c), 2e-3f);
      const vec3 albedo =
          surface_diffuse(scene, t, reference.barycentric.at(x, y, 0), reference.barycentric.at(x, y, 1));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.diffuse.at(x, y, c), albedo[c], 2e-2f);
      EXPECT_EQ(g.object.at(x, y), scene.triangle_object[t]);
    }
  EXPECT_GT(compared, 15000u);
}

TEST(RasterBench, ReportsOneTimingPerThreadCount) {
  const Scene scene = make_builtin_scene("cornell");
  Camera camera = scene.cameras.front().camera;
  camera.width = camera.height = 64;
  RasterBenchOptions options;
  options.threads = {1, 2};
  options.repetitions = 2;
  const std::vector<RasterTiming> t = bench_raster(scene, camera, options);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].threads, 1);
  EXPECT_EQ(t[1].threads, 2);
  for (const RasterTiming& timing : t) {
    EXPECT_GT(timing.depth_id_ms, 0.0);
    EXPECT_GT(timing.gbuffer_ms, 0.0);
    EXPECT_GT(timing.tris_per_s, 0.0);
    EXPECT_GT(timing.depth_id_stats.fragments_written, 0u);
  }
}

TEST(RasterBench, CompareIdBuffersCountsAgreement) {
  const Scene scene = make_builtin_scene("cornell");
  Camera camera = scene.cameras.front().camera;
  camera.width = camera.height = 32;
  const RasterImages raster = rasterize(scene, camera);
  IdAgreement same = compare_id_buffers(scene, camera, raster.triangle, raster.triangle);
  EXPECT_EQ(same.agree, same.pixels);
  ImageU32 wrong = raster.triangle;
  wrong.at(16, 16) = kNoTriangle;  // the back wall's center: no edge, no tie
  const IdAgreement a = compare_id_buffers(scene, camera, raster.triangle, wrong);
  EXPECT_EQ(a.agree, a.pixels - 1);
  EXPECT_EQ(a.other, 1u);
}

}  // namespace
}  // namespace proxima
