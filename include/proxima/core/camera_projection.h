// project() and unproject() for loops that send many points through one camera: their
// per-camera constants (the rotations, the focal length's tan, the image centre) computed
// once. The same operations on the same values as project() and unproject(), which are
// built on it: the same bits.
#pragma once

#include <optional>

#include "proxima/core/camera.h"

namespace proxima {

struct CameraProjection {
  explicit CameraProjection(const Camera& cam)
      : to_camera(glm::conjugate(cam.orientation)),
        to_world(cam.orientation),
        eye(cam.position),
        focal(focal_length_px(cam)),
        half_width(0.5f * float(cam.width)),
        half_height(0.5f * float(cam.height)) {}

  // World point → pixel coordinates and depth; nullopt when not in front (depth ≤ 0).
  std::optional<Projection> operator()(vec3 world) const {
    const vec3 c = to_camera * (world - eye);
    const float depth = -c.z;
    if (!(depth > 0.0f)) return std::nullopt;
    return Projection{vec2(half_width + focal * c.x / depth, half_height - focal * c.y / depth), depth};
  }

  // Pixel coordinates and depth (−z_cam) → world point.
  vec3 unproject(vec2 pixel, float depth) const {
    const vec3 c((pixel.x - half_width) * depth / focal, (half_height - pixel.y) * depth / focal, -depth);
    return to_world * c + eye;
  }

  quat to_camera, to_world;
  vec3 eye;
  float focal, half_width, half_height;
};

}  // namespace proxima
