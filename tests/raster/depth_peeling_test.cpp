// Depth peeling: every fragment of a pixel comes out in exactly one layer, in
// (depth, triangle id) order, coplanar duplicates included.
#include "proxima/raster/depth_peeling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <utility>

#include "proxima/scene/procedural.h"

namespace proxima {
namespace {

Scene nested_spheres() {
  Scene scene;
  const uint32_t mat = add_material(scene, Material{});
  add_object(scene, make_sphere(1.0f, 48, 24), "outer", mat);
  Mesh inner = make_sphere(0.5f, 32, 16);
  transform_mesh(inner, glm::translate(mat4(1.0f), vec3(0.2f, 0.1f, 0.0f)));
  add_object(scene, inner, "inner", mat);
  add_object(scene, inner, "inner-duplicate", mat);  // coplanar with "inner"
  return scene;
}

TEST(DepthPeeling, LayersEnumerateEveryFragmentInOrder) {
  const Scene scene = nested_spheres();
  const Camera camera = look_at(vec3(0.3f, 0.4f, 3.0f), vec3(0), vec3(0, 1, 0), 50.0f, 96, 96);
  // Every fragment of every pixel, from a depth-test-off pass.
  std::vector<std::vector<std::pair<float, uint32_t>>> all(size_t(96 * 96));
  RasterOptions off;
  off.depth_test = false;
  RasterImages unused;
  rasterize(scene, camera, off, unused, [&](const Fragment& f) {
    all[size_t(f.y) * 96 + size_t(f.x)].push_back({f.depth, f.triangle});
    return true;
  });
  DepthPeelOptions options;
  options.max_layers = 16;
  const std::vector<RasterImages> layers = depth_peel(scene, camera, options);
  ASSERT_EQ(layers.size(), 6u);  // outer front, 2 × inner front, 2 × inner back, outer back
  size_t pixels_with_six = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      auto expected = all[size_t(y) * 96 + size_t(x)];
      std::sort(expected.begin(), expected.end());
      std::vector<std::pair<float, uint32_t>> peeled;
      for (const RasterImages& layer : layers)
        if (layer.triangle.at(x, y) != kNoTriangle)
          peeled.push_back({layer.depth.at(x, y), layer.triangle.at(x, y)});
      EXPECT_EQ(peeled, expected) << x << "," << y;
      pixels_with_six += peeled.size() == 6;
    }
  EXPECT_GT(pixels_with_six, 500u);
}

TEST(DepthPeeling, MinSeparationMergesCoplanarSurfaces) {
  const Scene scene = nested_spheres();
  const Camera camera = look_at(vec3(0.3f, 0.4f, 3.0f), vec3(0), vec3(0, 1, 0), 50.0f, 64, 64);
  DepthPeelOptions options;
  options.max_layers = 16;
  options.min_separation = 1e-4f;
  EXPECT_EQ(depth_peel(scene, camera, options).size(), 4u);
}

TEST(DepthPeeling, EmptySceneHasNoLayers) {
  const Camera camera = look_at(vec3(0, 0, 3), vec3(0), vec3(0, 1, 0), 50.0f, 16, 16);
  EXPECT_TRUE(depth_peel(Scene{}, camera).empty());
}

}  // namespace
}  // namespace proxima
