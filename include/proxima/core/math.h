// Math types and small numeric helpers shared by every module (glm underneath).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace proxima {

using glm::mat3;
using glm::mat4;
using glm::quat;
using glm::uvec3;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::ivec2;
using glm::dvec3;

inline constexpr float kInf = std::numeric_limits<float>::infinity();
inline constexpr float kPi = 3.14159265358979323846f;

// Triangle id: index into Scene::triangles; kNoTriangle where nothing was hit.
inline constexpr uint32_t kNoTriangle = 0xFFFFFFFFu;

inline bool is_finite(vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Axis-aligned box; empty when min > max (the default).
struct Bounds3 {
  vec3 min{kInf};
  vec3 max{-kInf};

  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  void extend(vec3 p) { min = glm::min(min, p); max = glm::max(max, p); }
  void extend(const Bounds3& b) { min = glm::min(min, b.min); max = glm::max(max, b.max); }
  vec3 center() const { return 0.5f * (min + max); }
  vec3 extent() const { return max - min; }
  float diagonal() const { return empty() ? 0.0f : glm::length(max - min); }
  // Corner k in 0..7: bit 0 picks max.x, bit 1 max.y, bit 2 max.z.
  vec3 corner(int k) const {
    return vec3((k & 1) ? max.x : min.x, (k & 2) ? max.y : min.y, (k & 4) ? max.z : min.z);
  }
  // Distance from p to the farthest corner.
  float farthest_corner_distance(vec3 p) const { return glm::length(glm::max(glm::abs(min - p), glm::abs(max - p))); }
};

// Ray with parametric extent [tmin, tmax]; dir need not be normalized, t is in units of dir.
struct Ray {
  vec3 origin{0.0f};
  vec3 dir{0.0f, 0.0f, -1.0f};
  float tmin = 0.0f;
  float tmax = kInf;
};

}  // namespace proxima
