// Camera paths: key frames (position, target, fov) interpolated with
// uniform Catmull-Rom splines; frame F of a path with N frames is at time
// t0 + F·(t1 − t0)/(N − 1).
#pragma once

#include <string>
#include <vector>

#include "proxima/core/camera.h"

namespace proxima {

struct CameraKey {
  float time = 0.0f;
  vec3 position{0.0f};
  vec3 target{0.0f, 0.0f, -1.0f};
  float vfov_deg = 60.0f;
};

struct CameraPath {
  std::string name;
  std::vector<CameraKey> keys;  // sorted by time, at least one
  int frames = 100;             // frames the path is sampled into
  vec3 up{0.0f, 1.0f, 0.0f};
};

// Camera at time t on the path, with the given image size and clip distances. A time whose
// interpolated view is degenerate (target at the position, view along `up`, overflow)
// takes the view of the nearer key.
Camera camera_at_time(const CameraPath& path, float t, int width, int height, float near = 0.01f,
                      float far = 1000.0f);

// Time of frame `frame` (0 .. frames−1).
float frame_time(const CameraPath& path, int frame);

}  // namespace proxima
