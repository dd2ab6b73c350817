// Glossy clusters' lobe rays marched over block nearest depths (MarchOptions::coarse).
#include <gtest/gtest.h>

#include "proxima/reflect/cluster_reflection.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"

namespace proxima {

// Mirror samples keep their exact answer; glossy ones change by a small part of the
// reflected radiance (bathroom: mostly glossy tiles).
TEST(ClusterCoarseMarch, ChangesOnlyGlossySamplesAndLittle) {
  const Scene scene = make_builtin_scene("bathroom");
  const CameraPath& path = scene.camera_paths.front();
  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = 4;
  const float t = 0.5f * (path.keys.front().time + path.keys.back().time);
  const ReflectionFrame frame =
      prepare_reflection_frame(scene, camera_at_time(path, t, 128, 96, 0.01f, scene_far_plane(scene)), ro);
  ClusterReflectionOptions exact, coarse;
  coarse.glossy_march_coarse = 4;
  const ClusterReflections a = render_cluster_reflections(scene, frame, exact);
  const ClusterReflections b = render_cluster_reflections(scene, frame, coarse);
  ASSERT_EQ(a.radiance.size(), b.radiance.size());
  double diff = 0.0, level = 0.0;
  size_t glossy_changed = 0;
  for (size_t i = 0; i < a.radiance.size(); ++i) {
    if (a.radiance[i] != b.radiance[i]) {
      // A cluster is glossy when one of its samples is: only such clusters march coarsely.
      bool cluster_glossy = false;
      for (size_t j = 0; j < a.radiance.size(); ++j)
        if (a.cluster[j] == a.cluster[i] && frame.gloss[j] > 0.0f) {
          cluster_glossy = true;
          break;
        }
      ASSERT_TRUE(cluster_glossy) << "sample " << i;
      ++glossy_changed;
    }
    diff += glm::length(a.radiance[i] - b.radiance[i]);
    level += glm::length(a.radiance[i]);
  }
  EXPECT_GT(glossy_changed, 0u);
  EXPECT_LT(diff, 0.1 * level) << diff / double(a.radiance.size()) << " against " << level / double(a.radiance.size());
}

}  // namespace proxima
