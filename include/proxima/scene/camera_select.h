// Which camera of a scene an experiment renders from: a named or indexed scene camera, or a
// frame of a camera path; plus the clip range every path camera uses.
#pragma once

#include <string>

#include "proxima/core/camera.h"
#include "proxima/scene/scene.h"

namespace proxima {

// A camera by index or name, or a frame of a path by index or name. The error messages of
// pick_camera name the command-line flags --camera, --path and --frame.
struct CameraChoice {
  std::string camera;  // index or name; empty = the scene's first camera
  std::string path;    // camera path index or name; empty = none
  int frame = 0;
};

// Index of the camera path named `key` (or with index `key` when it is all digits); −1 if
// the scene has no such path.
int find_camera_path(const Scene& scene, const std::string& key);

// The camera path find_camera_path finds; throws InputError naming --path when there is none.
const CameraPath& camera_path(const Scene& scene, const std::string& key);

// Far clip distance for cameras inside or near the scene: 4 diagonals of its bounds, at
// least 10 m.
float scene_far_plane(const Scene& scene);

// Resolves the choice on a scene at the given resolution. A scene without cameras is viewed
// from the front (+Z), its bounds fitting the view. Throws InputError naming the flag.
Camera pick_camera(const Scene& scene, const CameraChoice& choice, int width, int height);

}  // namespace proxima
