// RasterOptions::triangle_runs draws exactly what the id list of the same triangles draws.
#include <gtest/gtest.h>

#include <algorithm>
#include <span>

#include "proxima/core/rng.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/scene/builtin_scenes.h"

namespace proxima {

TEST(RasterTriangleRuns, DrawTheSameAsTheIdListOfTheirTriangles) {
  // Random runs of up to 40 consecutive triangles of each object (about half of them kept),
  // each with its tight vertex range; neighbouring runs share vertices and some objects lie
  // outside the frustum. Depth, triangle and barycentric images and the counts must equal
  // those of the id list, for each of the scene's views.
  const Scene scene = make_builtin_scene("bathroom");
  ASSERT_GT(scene.objects.size(), 3u);
  Pcg32 rng(5);
  std::vector<TriangleRun> runs;
  std::vector<uint32_t> ids;
  for (const Object& obj : scene.objects) {
    for (uint32_t t = 0; t < obj.triangle_count;) {
      const uint32_t count = std::min<uint32_t>(1 + uint32_t(rng.next_float() * 40.0f), obj.triangle_count - t);
      if (rng.next_float() < 0.5f) {
        TriangleRun run{obj.first_triangle + t, count, ~0u, 0};
        uint32_t hi = 0;
        for (uint32_t i = run.first; i < run.first + count; ++i) {
          ids.push_back(i);
          for (int k = 0; k < 3; ++k) {
            run.first_vertex = std::min(run.first_vertex, scene.triangles[i][k]);
            hi = std::max(hi, scene.triangles[i][k]);
          }
        }
        run.vertex_count = hi - run.first_vertex + 1;
        runs.push_back(run);
      }
      t += count;
    }
  }
  ASSERT_GT(runs.size(), 20u);
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  int views = 0;
  for (const NamedCamera& named : scene.cameras) {
    Camera camera = named.camera;
    camera.width = 96;
    camera.height = 80;
    RasterOptions a, b;
    a.outputs = b.outputs = kRasterDepth | kRasterTriangle | kRasterBarycentric;
    a.object_bounds = b.object_bounds = bounds;
    a.triangles = ids;
    b.triangle_runs = runs;
    RasterImages ia, ib;
    const RasterStats sa = rasterize(scene, camera, a, ia, AcceptAllFragments{});
    const RasterStats sb = rasterize(scene, camera, b, ib, AcceptAllFragments{});
    auto bytes = [](const auto& image) { return std::as_bytes(image.data()); };
    EXPECT_TRUE(std::ranges::equal(bytes(ia.depth), bytes(ib.depth)));
    EXPECT_TRUE(std::ranges::equal(bytes(ia.triangle), bytes(ib.triangle)));
    EXPECT_TRUE(std::ranges::equal(bytes(ia.barycentric), bytes(ib.barycentric)));
    EXPECT_EQ(sa.objects_drawn, sb.objects_drawn);
    EXPECT_EQ(sa.triangles_submitted, sb.triangles_submitted);
    EXPECT_EQ(sa.triangles_rasterized, sb.triangles_rasterized);
    views += sa.triangles_rasterized > 0;
  }
  EXPECT_GT(views, 0);
}

}  // namespace proxima
