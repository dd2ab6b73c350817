// Culling of cluster depth images: exact (bit-identical images), and it draws less.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "proxima/reflect/cluster_depth_image.h"
#include "proxima/reflect/cluster_reflection.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"
#include "trace/test_geometry.h"

namespace proxima {

namespace {

template <typename T>
bool same_bits(const Image<T>& a, const Image<T>& b) {
  return a.width() == b.width() && a.height() == b.height() && a.channels() == b.channels() &&
         std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(T)) == 0;
}

bool same_images(const RasterImages& a, const RasterImages& b) {
  return same_bits(a.depth, b.depth) && same_bits(a.triangle, b.triangle) && same_bits(a.barycentric, b.barycentric);
}

// Frames along a built-in scene's first camera path, small and with glossy lobes, so the
// cluster cameras include planar, curved and glossy ones.
ReflectionFrame path_frame(const Scene& scene, int index) {
  const CameraPath& path = scene.camera_paths.front();
  const float t0 = path.keys.front().time, t1 = path.keys.back().time;
  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = 2;
  const float t = t0 + float(index) * (t1 - t0) / 3.0f;
  return prepare_reflection_frame(scene, camera_at_time(path, t, 128, 96, 0.01f, scene_far_plane(scene)), ro);
}

// The object a cluster's image leaves out: its reflector when the cluster is curved.
uint32_t excluded_object(const ReflectionFrame& frame, const ClusterReflections& cr, size_t c) {
  if (cr.cameras[c]->planar) return kNoObject;
  const auto it = std::find(cr.cluster.begin(), cr.cluster.end(), uint32_t(c));
  return frame.reflector[size_t(it - cr.cluster.begin())];
}

class ClusterDepthImage : public ::testing::TestWithParam<const char*> {};

}  // namespace

// Every cluster camera of several frames: the first and second layers drawn from the
// culled triangle list, with triangles far in front of the clip plane spared the
// per-fragment clip test (clip_margin), equal the layers drawn from the whole scene with
// every fragment tested, bit for bit.
TEST_P(ClusterDepthImage, CullingIsExact) {
  const Scene scene = make_builtin_scene(GetParam());
  const TriangleBlocks blocks = triangle_blocks(scene);
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  uint64_t cameras = 0, drawn_all = 0, drawn_culled = 0, covered = 0;
  std::vector<TriangleRun> list;
  for (int f = 0; f < 3; ++f) {
    const ReflectionFrame frame = path_frame(scene, f);
    const ClusterReflections cr = render_cluster_reflections(scene, frame, {}, bounds);
    for (size_t c = 0; c < cr.cameras.size(); ++c) {
      if (!cr.cameras[c]) continue;
      const ClusterCamera& k = *cr.cameras[c];
      ClusterDrawList whole, culled;
      whole.excluded_object = excluded_object(frame, cr, c);
      ASSERT_TRUE(cull_cluster_triangles(scene, blocks, k, whole.excluded_object, 1e-3f * frame.scene_diagonal, list));
      culled.culled = true;
      culled.triangles = list;
      culled.clip_margin = 1e-3f * frame.scene_diagonal;
      RasterImages a, b, a2, b2;
      const RasterStats sa = rasterize_cluster_image(scene, k, whole, a);
      const RasterStats sb = rasterize_cluster_image(scene, k, culled, b);
      ASSERT_TRUE(same_images(a, b)) << GetParam() << " frame " << f << " cluster " << c;
      rasterize_cluster_second_layer(scene, k, whole, a, 0.05f, a2);
      rasterize_cluster_second_layer(scene, k, culled, b, 0.05f, b2);
      ASSERT_TRUE(same_images(a2, b2)) << GetParam() << " frame " << f << " cluster " << c << " (second layer)";
      ++cameras;
      drawn_all += sa.triangles_submitted;
      drawn_culled += sb.triangles_submitted;
      for (uint32_t t : a.triangle.data()) covered += t != kNoTriangle;
    }
  }
  EXPECT_GE(cameras, 10u);
  EXPECT_GT(covered, 1000u);  // the images are not empty
  // Culling leaves triangles out (how many depends on the scene: frusta of curved and
  // glossy clusters hold most of a room).
  EXPECT_LT(drawn_culled, drawn_all) << drawn_culled << " of " << drawn_all;
}

// A curved cluster's own reflector is left out with or without culling.
TEST_P(ClusterDepthImage, CullingLeavesTheExcludedObjectOut) {
  const Scene scene = make_builtin_scene(GetParam());
  const TriangleBlocks blocks = triangle_blocks(scene);
  const ReflectionFrame frame = path_frame(scene, 1);
  const ClusterReflections cr = render_cluster_reflections(scene, frame, {});
  std::vector<TriangleRun> list;
  uint64_t checked = 0;
  for (size_t c = 0; c < cr.cameras.size(); ++c) {
    if (!cr.cameras[c] || cr.cameras[c]->planar) continue;
    const uint32_t reflector = excluded_object(frame, cr, c);
    ClusterDrawList whole, culled;
    whole.excluded_object = reflector;
    ASSERT_TRUE(cull_cluster_triangles(scene, blocks, *cr.cameras[c], reflector, 1e-3f * frame.scene_diagonal, list));
    for (const TriangleRun& run : list)
      for (uint32_t t = run.first; t < run.first + run.count; ++t) ASSERT_NE(scene.triangle_object[t], reflector);
    culled.culled = true;
    culled.triangles = list;
    RasterImages a, b;
    rasterize_cluster_image(scene, *cr.cameras[c], whole, a);
    rasterize_cluster_image(scene, *cr.cameras[c], culled, b);
    ASSERT_TRUE(same_images(a, b)) << GetParam() << " cluster " << c;
    ++checked;
  }
  EXPECT_GT(checked, 0u);
}

// The method's output does not change with culling.
TEST_P(ClusterDepthImage, ReflectionsAreIdenticalWithAndWithoutCulling) {
  const Scene scene = make_builtin_scene(GetParam());
  const ReflectionFrame frame = path_frame(scene, 2);
  ClusterReflectionOptions on, off;
  off.cull = false;
  const ClusterReflections a = render_cluster_reflections(scene, frame, on);
  const ClusterReflections b = render_cluster_reflections(scene, frame, off);
  ASSERT_GT(a.radiance.size(), 100u);
  EXPECT_TRUE(a.radiance == b.radiance);
  EXPECT_TRUE(a.flags == b.flags);
  EXPECT_EQ(a.stats.texels, b.stats.texels);
  EXPECT_EQ(a.stats.second_layer_texels, b.stats.second_layer_texels);
  EXPECT_LT(a.stats.triangles_drawn, b.stats.triangles_drawn);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, ClusterDepthImage, ::testing::Values("living-room", "bathroom"));

TEST(TriangleBlocks, CoverEveryTriangleOnceWithinItsObject) {
  // ... and each block's vertex range holds its triangles' vertices.
  Scene scene;
  const uint32_t m = test::add_diffuse(scene, vec3(0.5f));
  add_object(scene, test::sphere_mesh(vec3(0.0f), 1.0f, 24, 12), "a", m);
  add_object(scene, test::quad_mesh(vec3(2, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)), "b", m);
  const TriangleBlocks blocks = triangle_blocks(scene, 64);
  ASSERT_EQ(blocks.object_first_block.size(), 3u);
  std::vector<int> seen(scene.triangles.size(), 0);
  for (uint32_t o = 0; o < 2; ++o)
    for (uint32_t i = blocks.object_first_block[o]; i < blocks.object_first_block[o + 1]; ++i) {
      EXPECT_LE(blocks.count[i], 64u);
      for (uint32_t t = blocks.first[i]; t < blocks.first[i] + blocks.count[i]; ++t) {
        ++seen[t];
        EXPECT_EQ(scene.triangle_object[t], o);
        const uvec3 idx = scene.triangles[t];
        for (int k = 0; k < 3; ++k) {
          const vec3 p = scene.positions[idx[k]];
          EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, blocks.bounds[i].min)) &&
                      glm::all(glm::lessThanEqual(p, blocks.bounds[i].max)));
          EXPECT_GE(idx[k], blocks.first_vertex[i]);
          EXPECT_LT(idx[k] - blocks.first_vertex[i], blocks.vertex_count[i]);
        }
      }
    }
  for (int s : seen) EXPECT_EQ(s, 1);
}

}  // namespace proxima
