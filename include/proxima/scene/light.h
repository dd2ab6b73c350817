// Lights: point, rectangular area, and the environment (constant color or cube map).
#pragma once

#include <array>

#include "proxima/core/image.h"
#include "proxima/core/math.h"

namespace proxima {

// Isotropic point light; irradiance at distance r facing it is intensity / r².
struct PointLight {
  vec3 position{0.0f};
  vec3 intensity{1.0f};
};

// One-sided rectangle: corner + a·edge_u + b·edge_v for a, b in [0, 1]; emits constant
// radiance on the side of normal = normalize(cross(edge_u, edge_v)).
struct AreaLight {
  vec3 corner{0.0f};
  vec3 edge_u{1.0f, 0.0f, 0.0f};
  vec3 edge_v{0.0f, 0.0f, 1.0f};
  vec3 radiance{1.0f};

  vec3 normal() const { return glm::normalize(glm::cross(edge_u, edge_v)); }
  float area() const { return glm::length(glm::cross(edge_u, edge_v)); }
  vec3 point(float a, float b) const { return corner + a * edge_u + b * edge_v; }
};

// Radiance arriving along directions that escape the scene. With a cube map (faces in
// CubeFace order, the layout of core/cube_camera.h), the map is used; otherwise `color`.
struct Environment {
  vec3 color{0.0f};
  std::array<ImageF, 6> cube;  // empty images when there is no map

  bool has_cube_map() const { return !cube[0].empty(); }
};

// Radiance from the environment along world direction dir (need not be unit).
vec3 environment_radiance(const Environment& env, vec3 dir);

}  // namespace proxima
