// Levels of detail by vertex clustering, and cluster images drawn from them.
#include <gtest/gtest.h>

#include <cmath>

#include "proxima/reflect/cluster_reflection.h"
#include "proxima/reflect/scene_lod.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"

namespace proxima {

namespace {

ReflectionFrame path_frame(const Scene& scene) {
  const CameraPath& path = scene.camera_paths.front();
  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = 2;
  const float t = 0.5f * (path.keys.front().time + path.keys.back().time);
  return prepare_reflection_frame(scene, camera_at_time(path, t, 128, 96, 0.01f, scene_far_plane(scene)), ro);
}

}  // namespace

// Level 0 is the scene; every coarser level has fewer triangles, each of them standing for a
// source triangle of its object whose vertices lie within a cell diagonal of its own.
TEST(SceneLod, LevelsShrinkAndStayWithinACell) {
  const Scene scene = make_builtin_scene("living-room");
  const std::vector<float> cells = lod_cells(scene_bounds(scene).diagonal(), 9);
  ASSERT_EQ(cells.size(), 8u);
  const SceneLod lod = build_scene_lod(scene, cells);
  ASSERT_EQ(lod.levels(), 9u);
  ASSERT_EQ(lod.objects.size(), 9 * scene.objects.size());
  ASSERT_EQ(lod.triangles.size(), lod.source_triangle.size());
  uint64_t previous = 0;
  for (uint32_t level = 0; level < lod.levels(); ++level) {
    uint64_t count = 0;
    for (uint32_t o = 0; o < lod.source_objects; ++o) {
      const Object& obj = lod.objects[lod.object(level, o)];
      count += obj.triangle_count;
      for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
        const uint32_t s = lod.source_triangle[t];
        ASSERT_EQ(scene.triangle_object[s], o);
        ASSERT_EQ(lod.triangle_object[t], lod.object(level, o));
        if (level == 0) {
          ASSERT_EQ(lod.triangles[t], scene.triangles[s]);
          continue;
        }
        const float reach = std::sqrt(3.0f) * cells[level - 1] * 1.0001f;
        for (int k = 0; k < 3; ++k)
          ASSERT_LE(glm::length(scene.positions[lod.triangles[t][k]] - scene.positions[scene.triangles[s][k]]), reach);
      }
    }
    if (level == 0) EXPECT_EQ(count, scene.triangles.size());
    else EXPECT_LE(count, previous);
    previous = count;
  }
  EXPECT_LT(previous, scene.triangles.size() / 10) << "the coarsest level keeps " << previous;
}

// A level-of-detail factor too small for any level draws the exact triangles through the
// level-0 copy: the same reflections bit for bit (the ids map back to the source triangles).
TEST(SceneLod, LevelZeroGivesTheExactReflections) {
  const Scene scene = make_builtin_scene("bathroom");
  const ReflectionFrame frame = path_frame(scene);
  ClusterReflectionOptions exact, lod0;
  lod0.lod_texels = 1e-6f;
  const ClusterReflections a = render_cluster_reflections(scene, frame, exact);
  const ClusterReflections b = render_cluster_reflections(scene, frame, lod0);
  ASSERT_GT(a.radiance.size(), 100u);
  EXPECT_TRUE(a.radiance == b.radiance);
  EXPECT_TRUE(a.flags == b.flags);
  EXPECT_EQ(a.stats.triangles_drawn, b.stats.triangles_drawn);
}

// Coarser levels draw fewer triangles and change the reflections only a little (on a
// 128 × 96 frame; docs/journal/cluster.md has the errors at 512²).
TEST(SceneLod, CoarseLevelsDrawLessWithSmallError) {
  const Scene scene = make_builtin_scene("living-room");
  const ReflectionFrame frame = path_frame(scene);
  ClusterReflectionOptions exact, coarse;
  coarse.lod_texels = 1.0f;
  const ClusterReflections a = render_cluster_reflections(scene, frame, exact);
  const ClusterReflections b = render_cluster_reflections(scene, frame, coarse);
  ASSERT_EQ(a.radiance.size(), b.radiance.size());
  EXPECT_LT(b.stats.triangles_drawn, a.stats.triangles_drawn * 3 / 4) << b.stats.triangles_drawn << " of "
                                                                      << a.stats.triangles_drawn;
  // The mean change of a sample's reflected radiance is a small part of the radiance.
  double diff = 0.0, level = 0.0;
  for (size_t i = 0; i < a.radiance.size(); ++i) {
    diff += glm::length(a.radiance[i] - b.radiance[i]);
    level += glm::length(a.radiance[i]);
  }
  EXPECT_GT(diff, 0.0);
  EXPECT_LT(diff, 0.1 * level) << diff / double(a.radiance.size()) << " against " << level / double(a.radiance.size());
}

}  // namespace proxima
