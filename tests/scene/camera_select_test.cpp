#include "proxima/scene/camera_select.h"

#include <gtest/gtest.h>

#include "proxima/core/error.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_path.h"

namespace proxima {
namespace {

std::string input_error(const Scene& scene, const CameraChoice& choice) {
  try {
    pick_camera(scene, choice, 64, 48);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CameraSelect, FindsPathsByIndexAndName) {
  const Scene scene = make_builtin_scene("living-room");
  ASSERT_FALSE(scene.camera_paths.empty());
  const std::string name = scene.camera_paths[0].name;
  EXPECT_EQ(find_camera_path(scene, name), 0);
  EXPECT_EQ(find_camera_path(scene, "0"), 0);
  EXPECT_EQ(find_camera_path(scene, std::to_string(scene.camera_paths.size())), -1);
  EXPECT_EQ(find_camera_path(scene, "no-such-path"), -1);
  EXPECT_EQ(find_camera_path(scene, "99999999999999999999999"), -1);  // no overflow
}

TEST(CameraSelect, PathFrameUsesTheSceneFarPlane) {
  const Scene scene = make_builtin_scene("living-room");
  const CameraPath& path = scene.camera_paths[0];
  const Camera cam = pick_camera(scene, {"", path.name, 3}, 64, 48);
  const Camera expected = camera_at_time(path, frame_time(path, 3), 64, 48, 0.01f, scene_far_plane(scene));
  EXPECT_EQ(cam.position, expected.position);
  EXPECT_EQ(cam.far, expected.far);
  EXPECT_EQ(cam.width, 64);
  EXPECT_GE(scene_far_plane(scene), 10.0f);
  EXPECT_GE(scene_far_plane(scene), 4.0f * scene_bounds(scene).diagonal());
}

TEST(CameraSelect, ErrorsNameTheFlag) {
  const Scene scene = make_builtin_scene("living-room");
  EXPECT_NE(input_error(scene, {"", "no-such-path", 0}).find("--path"), std::string::npos);
  EXPECT_NE(input_error(scene, {"", scene.camera_paths[0].name, 1 << 30}).find("--frame"), std::string::npos);
  EXPECT_NE(input_error(scene, {"no-such-camera", "", 0}).find("--camera"), std::string::npos);
  EXPECT_THROW(pick_camera(scene, {}, 0, 48), InputError);
}

}  // namespace
}  // namespace proxima
