#include "proxima/scene/camera_select.h"

#include <algorithm>

#include "proxima/core/error.h"
#include "proxima/scene/camera_path.h"

namespace proxima {

namespace {

// Index (all digits) or name lookup; −1 if absent.
template <typename T, typename NameOf>
int find_by_index_or_name(const std::vector<T>& items, const std::string& key, NameOf name_of) {
  if (!key.empty() && key.find_first_not_of("0123456789") == std::string::npos) {
    if (key.size() > 9) return -1;
    size_t i = std::stoul(key);
    return i < items.size() ? int(i) : -1;
  }
  for (size_t i = 0; i < items.size(); ++i)
    if (name_of(items[i]) == key) return int(i);
  return -1;
}

}  // namespace

int find_camera_path(const Scene& scene, const std::string& key) {
  return find_by_index_or_name(scene.camera_paths, key, [](const CameraPath& c) { return c.name; });
}

const CameraPath& camera_path(const Scene& scene, const std::string& key) {
  const int p = find_camera_path(scene, key);
  if (p < 0)
    fail_input("--path: scene '" + scene.name + "' has no camera path '" + key + "' (" +
               std::to_string(scene.camera_paths.size()) + " paths)");
  return scene.camera_paths[size_t(p)];
}

float scene_far_plane(const Scene& scene) { return std::max(10.0f, 4.0f * scene_bounds(scene).diagonal()); }

Camera pick_camera(const Scene& scene, const CameraChoice& choice, int width, int height) {
  Camera cam;
  if (!choice.path.empty()) {
    const CameraPath& path = camera_path(scene, choice.path);
    if (choice.frame < 0 || choice.frame >= path.frames)
      fail_input("--frame: " + std::to_string(choice.frame) + " is outside path '" + path.name + "' (0.." +
                 std::to_string(path.frames - 1) + ")");
    cam = camera_at_time(path, frame_time(path, choice.frame), width, height, 0.01f, scene_far_plane(scene));
  } else if (!scene.cameras.empty()) {
    const int c = choice.camera.empty()
                      ? 0
                      : find_by_index_or_name(scene.cameras, choice.camera, [](const NamedCamera& n) { return n.name; });
    if (c < 0)
      fail_input("--camera: scene '" + scene.name + "' has no camera '" + choice.camera + "' (" +
                 std::to_string(scene.cameras.size()) + " cameras)");
    cam = scene.cameras[size_t(c)].camera;
  } else {
    if (!choice.camera.empty()) fail_input("--camera: scene '" + scene.name + "' has no cameras");
    // No camera in the file: look at the bounds from the front (+Z), fitting them in view.
    const Bounds3 b = scene_bounds(scene);
    const float r = 0.5f * b.diagonal();
    const vec3 c = b.center();
    // Clip distances scale with the scene (r > 0: sanitized scenes have a triangle of
    // non-zero area), so micrometer-sized models are not clipped away.
    cam = look_at(c + vec3(0.0f, 0.25f * r, 2.5f * r), c, {0, 1, 0}, 45.0f, width, height, 0.01f * r, 10.0f * r);
  }
  cam.width = width;
  cam.height = height;
  validate_camera(cam, "--width/--height");
  return cam;
}

}  // namespace proxima
