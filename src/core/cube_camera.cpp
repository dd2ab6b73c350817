#include "proxima/core/cube_camera.h"

#include <cmath>

namespace proxima {
namespace {

// Face view axes and up vectors: the four side faces keep +Y up (upright images), the
// +Y face has +Z up and the −Y face −Z up.
struct FaceFrame {
  vec3 axis;
  vec3 up;
};
constexpr FaceFrame kFaces[6] = {
    {{1, 0, 0}, {0, 1, 0}},  {{-1, 0, 0}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, 1}},
    {{0, -1, 0}, {0, 0, -1}}, {{0, 0, 1}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}},
};

}  // namespace

Camera face_camera(const CubeCamera& cube, int face) {
  const FaceFrame& f = kFaces[face];
  return look_at(cube.center, cube.center + f.axis, f.up, 90.0f, cube.resolution, cube.resolution,
                 cube.near, cube.far);
}

std::array<Camera, 6> face_cameras(const CubeCamera& cube) {
  std::array<Camera, 6> cams;
  for (int i = 0; i < 6; ++i) cams[size_t(i)] = face_camera(cube, i);
  return cams;
}

CubeTexel cube_lookup(const CubeCamera& cube, vec3 dir) {
  vec3 a = glm::abs(dir);
  int face;
  if (a.x >= a.y && a.x >= a.z) face = dir.x >= 0.0f ? 0 : 1;
  else if (a.y >= a.z) face = dir.y >= 0.0f ? 2 : 3;
  else face = dir.z >= 0.0f ? 4 : 5;
  // Project in the face's camera frame directly (no world offset: avoids cancellation).
  const FaceFrame& f = kFaces[face];
  vec3 right = glm::normalize(glm::cross(f.axis, f.up));
  vec3 up = glm::cross(right, f.axis);
  float depth = glm::dot(dir, f.axis);
  float half = 0.5f * float(cube.resolution);
  vec2 pixel(half + half * glm::dot(dir, right) / depth, half - half * glm::dot(dir, up) / depth);
  return {face, pixel};
}

}  // namespace proxima
