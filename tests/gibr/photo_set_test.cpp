// Camera file of calibrated photographs: exact round trip of intrinsics and pose; malformed
// files are InputErrors naming the file.
#include "proxima/gibr/photo_set.h"

#include <gtest/gtest.h>

#include "../test_util.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::gibr {
namespace {

// Off-path novel views: deterministic, the path's orientation, moved off the path by at most
// the offset's step and never through a surface.
TEST(GibrOffpathPoses, DeterministicOffThePathAndInFreeSpace) {
  const Scene scene = make_vis_rooms();
  const RayScene rays(scene);
  const CameraPath& path = scene.camera_paths.front();
  const double offset = 0.5;
  const std::vector<Camera> a = offpath_poses(rays, path, 8, 64, 48, offset, 0.01f, 100.0f);
  const std::vector<Camera> b = offpath_poses(rays, path, 8, 64, 48, offset, 0.01f, 100.0f);
  ASSERT_EQ(a.size(), 8u);
  int moved = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position) << i;
    EXPECT_EQ(a[i].orientation, b[i].orientation) << i;
    const float t = path.keys.front().time + (path.keys.back().time - path.keys.front().time) * float(i) / 7.0f;
    const Camera on = camera_at_time(path, t, 64, 48, 0.01f, 100.0f);
    EXPECT_EQ(a[i].orientation, on.orientation) << i;
    const vec3 d = a[i].position - on.position;
    const float len = glm::length(d);
    EXPECT_LE(len, float(offset) * std::sqrt(1.25f) + 1e-4f) << i;
    if (len > 1e-4f) {
      ++moved;
      EXPECT_FALSE(rays.occluded(Ray{on.position, d / len, 0.0f, len})) << i;
    }
  }
  EXPECT_GE(moved, 4);
}

TEST(GibrCameraFile, RoundTripsIntrinsicsAndPose) {
  TempDir dir;
  const Camera cam = look_at({1.0f, 1.6f, 2.0f}, {4.0f, 1.2f, 1.0f}, {0, 1, 0}, 65.0f, 320, 240, 0.01f, 500.0f);
  write_camera_file(dir.path / "cameras.json", {{"photo_000.png", cam}});
  const std::vector<CalibratedPhoto> back = read_camera_file(dir.path / "cameras.json");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].image, "photo_000.png");
  EXPECT_EQ(back[0].camera.width, 320);
  EXPECT_EQ(back[0].camera.vfov_deg, 65.0f);
  EXPECT_EQ(back[0].camera.position, cam.position);
  EXPECT_NEAR(glm::length(camera_forward(back[0].camera) - camera_forward(cam)), 0.0f, 1e-6f);
}

TEST(GibrCameraFile, MalformedFilesNameTheFile) {
  TempDir dir;
  const auto p = dir.path / "bad.json";
  EXPECT_NE(error_of([&] { read_camera_file(p); }).find("bad.json"), std::string::npos);
  for (const char* text : {"{", "{\"format\": \"other\", \"version\": 1, \"photos\": []}",
                           "{\"format\": \"proxima-cameras\", \"version\": 1, \"photos\": [{\"image\": \"a.png\"}]}",
                           "{\"format\": \"proxima-cameras\", \"version\": 1, \"photos\": [{\"image\": \"a.png\", "
                           "\"width\": 0, \"height\": 2, \"vfov_deg\": 60, \"position\": [0,0,0], "
                           "\"orientation\": [1,0,0,0]}]}",
                           // Numbers no int holds are refused, not converted.
                           "{\"format\": \"proxima-cameras\", \"version\": 1, \"photos\": [{\"image\": \"a.png\", "
                           "\"width\": 1e300, \"height\": 2, \"vfov_deg\": 60, \"position\": [0,0,0], "
                           "\"orientation\": [1,0,0,0]}]}",
                           "{\"format\": \"proxima-cameras\", \"version\": 1e300, \"photos\": []}"}) {
    write_file(p, text);
    EXPECT_NE(error_of([&] { read_camera_file(p); }).find("bad.json"), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace proxima::gibr
