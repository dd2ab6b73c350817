// Depth-only rasterization on the calling thread: bit-identical depth to the tiled
// rasterizer (near/far clipping, guard band, culling, tiny triangles), and its counts; with a
// mask of the texels needed, the same depth there.
#include "proxima/raster/depth_raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/error.h"
#include "proxima/scene/procedural.h"

namespace proxima {
namespace {

// Spheres of many tiny triangles, a torus, a wide plane through the near and far planes,
// and a box outside the frustum.
Scene clutter() {
  Scene s;
  const uint32_t mat = add_material(s, Material{});
  for (int i = 0; i < 5; ++i) {
    Mesh m = make_sphere(0.3f + 0.1f * float(i), 96, 48);
    transform_mesh(m, glm::translate(mat4(1.0f), vec3(float(i) * 0.5f - 1.0f, 0.2f * float(i), -float(i) * 0.4f)));
    add_object(s, m, "sphere", mat);
  }
  Mesh torus = make_torus(1.0f, 0.2f, 64, 32);
  transform_mesh(torus, glm::rotate(mat4(1.0f), 0.7f, vec3(1, 0, 0)));
  add_object(s, torus, "torus", mat);
  Mesh ground = make_plane(200.0f, 200.0f, 40, 40);
  transform_mesh(ground, glm::translate(mat4(1.0f), vec3(0, -0.8f, 0)));
  add_object(s, ground, "ground", mat);
  Mesh box = make_box(vec3(1.0f));
  transform_mesh(box, glm::translate(mat4(1.0f), vec3(0, 0, 40.0f)));
  add_object(s, box, "behind", mat);
  return s;
}

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

// With a mask of needed texels (a scattered set, as receivers read a shadow map), those
// texels get the depth drawn without it and fewer triangles are set up; a mask of another
// size is bad input.
TEST(DepthRaster, NeededTexelsGetTheSameDepth) {
  const Scene scene = clutter();
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  const Camera camera = look_at(vec3(0.3f, 0.5f, 3.0f), vec3(0), vec3(0, 1, 0), 60.0f, 211, 157, 0.05f, 6.0f);
  TexelMask needed;
  needed.reset(camera.width, camera.height);
  size_t count = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      if ((x * 7 + y * 13) % 29 == 0) {
        needed.set(x, y);
        ++count;
      }
  DepthRasterScratch scratch;
  ImageF all, some;
  const RasterStats st_all = rasterize_depth_serial(scene, camera, bounds, CullMode::None, all, scratch);
  const RasterStats st_some = rasterize_depth_serial(scene, camera, bounds, CullMode::None, &needed, some, scratch);
  size_t same = 0, covered = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      if ((x * 7 + y * 13) % 29 == 0) {
        same += std::memcmp(&all.at(x, y), &some.at(x, y), sizeof(float)) == 0;
        covered += !std::isinf(all.at(x, y));
      }
  EXPECT_EQ(same, count);
  EXPECT_GT(covered, count / 2);
  EXPECT_LT(st_some.triangles_rasterized, st_all.triangles_rasterized / 2);
  EXPECT_EQ(st_some.triangles_clipped, st_all.triangles_clipped);
  TexelMask wrong;
  wrong.reset(camera.width + 64, camera.height);
  EXPECT_THROW(rasterize_depth_serial(scene, camera, bounds, CullMode::None, &wrong, some, scratch), InputError);
}

}  // namespace
}  // namespace proxima
