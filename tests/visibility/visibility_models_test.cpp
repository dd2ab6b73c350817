// The visibility test models: polygon counts near the paper's (Figure 7), walkthrough
// paths of ≥ 100 frames, building floors scaling, bad floor counts rejected.
#include "proxima/scene/visibility_models.h"

#include <gtest/gtest.h>

#include "proxima/core/error.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/visibility/polygons.h"

namespace proxima {
namespace {

TEST(VisibilityModels, PolygonCountsAndPaths) {
  struct Want {
    const char* name;
    size_t lo, hi;
  } wants[] = {{"rooms", 20, 20}, {"maze", 280, 340}, {"arena", 640, 690}, {"vcity", 1126, 1126},
               {"floor", 1650, 1850}, {"building", 9000, 10500}};
  for (const Want& w : wants) {
    Scene s = make_builtin_scene(w.name);
    visibility::ModelPolygons m = visibility::extract_polygons(s);
    EXPECT_GE(m.polygons.size(), w.lo) << w.name;
    EXPECT_LE(m.polygons.size(), w.hi) << w.name;
    EXPECT_EQ(m.polygons.size() * 2, s.triangles.size()) << w.name << ": every quad merges into one polygon";
    ASSERT_FALSE(s.camera_paths.empty());
    EXPECT_GE(s.camera_paths.front().frames, 100) << w.name;
  }
}

TEST(VisibilityModels, BuildingFloorsScaleAndAreChecked) {
  const size_t one = visibility::extract_polygons(make_vis_building(1)).polygons.size();
  const size_t two = visibility::extract_polygons(make_vis_building(2)).polygons.size();
  EXPECT_GT(two, one * 19 / 10);
  EXPECT_THROW(make_vis_building(0), InputError);
  EXPECT_THROW(make_vis_building(65), InputError);
}

}  // namespace
}  // namespace proxima
