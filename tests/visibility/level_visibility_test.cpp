// Exact visibility on brush-built levels (level-*): the bounds of the synthetic models held
// on every viewpoint of geometry with coplanar overlaps, T-junctions, unwelded seams and
// slivers — agreement with Embree ≥ 99.9 % (but on the listed known misses), interior
// agreement ≥ 99.99 % (coplanar ties counting as agreement: either polygon is right there),
// no occluded label, no unplaced fragment, and every map passing its self-check (no holes:
// the regions tile the image). The failures these bounds catch: cracks (regions covering
// less than the image, found by the self-check's area test), unplaced fragments, views far
// below the agreement bound.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "proxima/scene/builtin_scenes.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/map_check.h"
#include "proxima/visibility/oracle.h"
#include "proxima/scene/camera_select.h"

namespace proxima::visibility {
namespace {

// Checks every `frame_step`-th viewpoint; returns the frames whose overall agreement (with
// ties) is below 99.9 %, which the callers compare with the documented known misses. The
// oracle and the self-check trace the welded scene the map is exact for.
std::vector<int> check_level(const char* name, int frame_step) {
  const Scene scene = make_builtin_scene(name);
  const ModelPolygons model = extract_polygons(scene);
  BspStats bsp;
  const WingedPair wp = build_winged_pair(model, {}, &bsp);
  EXPECT_EQ(bsp.unplaced_fragments, 0u) << name;
  const Scene welded = welded_scene(scene, model);
  const RayScene rays(welded);
  const CameraPath& path = scene.camera_paths.front();
  const float far = scene_far_plane(scene);
  std::vector<int> below;
  for (int frame = 0; frame < path.frames; frame += frame_step) {
    const Camera cam = camera_at_time(path, frame_time(path, frame), 512, 384, 1e-3f, far);
    const VisibilityMap map = trace_visibility_map(wp, cam);
    const MapCheck check = check_visibility_map(map, model, rays, cam);
    EXPECT_TRUE(check.pass) << name << " frame " << frame << ": " << check.reason;
    const OracleCounts c = compare_with_ray_casts(map, model, welded, rays, cam);
    if (c.agreement_with_ties_pct() < 99.9) below.push_back(frame);
    EXPECT_GE(c.interior_with_ties_pct(), 99.99) << name << " frame " << frame;
    EXPECT_EQ(c.occluded_label, 0u) << name << " frame " << frame;
  }
  return below;
}

// No known misses: the pixel columns beside an edge that welding and plane snapping moved
// (small frame 35, medium frame 96) are snap ties (docs/visibility.md, "What the map is
// exact for").
TEST(LevelVisibility, SmallLevelEveryViewpoint) {
  EXPECT_EQ(check_level("level-small", 1), (std::vector<int>{}));
}

TEST(LevelVisibility, MediumLevelEveryViewpoint) {
  EXPECT_EQ(check_level("level-medium", 1), (std::vector<int>{}));
}

TEST(LevelVisibility, HugeLevelEveryFifthViewpoint) {
  EXPECT_EQ(check_level("level-huge", 5), (std::vector<int>{}));
}

}  // namespace
}  // namespace proxima::visibility
