// Depth-only rasterization on the calling thread: bit-identical depth to the tiled
// rasterizer (near/far clipping, guard band, culling, tiny triangles), and its counts.
#include "proxima/raster/depth_raster.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "clutter_scene.h"

namespace proxima {
namespace {

using raster_test::clutter;

TEST(DepthRaster, BitIdenticalToTheTiledRasterizer) {
  const Scene scene = clutter();
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  DepthRasterScratch scratch;
  for (CullMode cull : {CullMode::None, CullMode::Back})
    for (const Camera& camera : {look_at(vec3(0.3f, 0.5f, 3.0f), vec3(0), vec3(0, 1, 0), 60.0f, 211, 157, 0.05f, 6.0f),
                                 look_at(vec3(-2.0f, 2.0f, 2.0f), vec3(0), vec3(0, 1, 0), 100.0f, 64, 300, 0.5f, 100.0f)}) {
      RasterOptions o;
      o.outputs = kRasterDepth;
      o.cull = cull;
      RasterStats tiled_stats;
      const RasterImages tiled = rasterize(scene, camera, o, &tiled_stats);
      ImageF depth;
      for (std::span<const Bounds3> b : {std::span<const Bounds3>(bounds), std::span<const Bounds3>()}) {
        const RasterStats st = rasterize_depth_serial(scene, camera, b, cull, depth, scratch);
        EXPECT_TRUE(depth == tiled.depth);
        EXPECT_EQ(st.triangles_rasterized, tiled_stats.triangles_rasterized);
        EXPECT_EQ(st.triangles_clipped, tiled_stats.triangles_clipped);
        EXPECT_EQ(st.triangles_culled, tiled_stats.triangles_culled);
        EXPECT_EQ(st.objects_culled, tiled_stats.objects_culled);
        EXPECT_GT(st.triangles_clipped, 0u);
        EXPECT_GT(st.triangles_rasterized, 10000u);
      }
    }
}

}  // namespace
}  // namespace proxima
