#include "proxima/scene/camera_path.h"

#include <gtest/gtest.h>

namespace proxima {
namespace {

CameraPath path_of(std::vector<CameraKey> keys) {
  CameraPath p;
  p.keys = std::move(keys);
  p.frames = 9;
  return p;
}

TEST(CameraPath, KeysAreHitExactlyAndFramesSpanTheKeys) {
  const CameraPath p = path_of({{0.0f, {0, 0, 5}, {0, 0, 0}, 60.0f}, {2.0f, {5, 0, 0}, {0, 0, 0}, 40.0f}});
  EXPECT_EQ(frame_time(p, 0), 0.0f);
  EXPECT_EQ(frame_time(p, 8), 2.0f);
  const Camera end = camera_at_time(p, 2.0f, 64, 48);
  EXPECT_EQ(end.position, vec3(5, 0, 0));
  EXPECT_EQ(end.vfov_deg, 40.0f);
}

// Two valid keys whose spline puts the position on the target half-way (a dolly through
// the look-at point) leave no view direction there; the frame keeps the nearer key's view
// direction instead of becoming a NaN camera.
TEST(CameraPath, TargetPassingThroughThePositionKeepsAValidCamera) {
  const CameraPath p = path_of({{0.0f, {0, 0, 0}, {0, 0, -1}, 60.0f}, {1.0f, {0, 0, -2}, {0, 0, -1}, 60.0f}});
  for (int f = 0; f < p.frames; ++f) {
    const Camera cam = camera_at_time(p, frame_time(p, f), 64, 48);
    EXPECT_NO_THROW(validate_camera(cam, "path")) << "frame " << f;
  }
  const Camera mid = camera_at_time(p, 0.5f, 64, 48);
  EXPECT_NEAR(mid.position.z, -1.0f, 1e-6f);
  EXPECT_NEAR(camera_forward(mid).z, 1.0f, 1e-6f);  // w = 0.5: the second key's view direction, +z
}

// Keys looking up-left and up-right interpolate to looking straight
// up, parallel to `up`, where look_at has no right vector.
TEST(CameraPath, ViewSweepingThroughUpKeepsAValidCamera) {
  const CameraPath p = path_of({{0.0f, {0, 0, 0}, {-1, 1, 0}, 60.0f}, {1.0f, {0, 0, 0}, {1, 1, 0}, 60.0f}});
  for (int f = 0; f < p.frames; ++f)
    EXPECT_NO_THROW(validate_camera(camera_at_time(p, frame_time(p, f), 64, 48), "path")) << "frame " << f;
}

}  // namespace
}  // namespace proxima
