// Hand-built meshes for the trace/ tests, independent of the procedural generators so the
// tests know the exact geometry they check against.
#pragma once

#include <cmath>

#include "proxima/scene/mesh.h"
#include "proxima/scene/scene.h"

namespace proxima::test {

// Parallelogram corner + a·eu + b·ev, two triangles, front side = cross(eu, ev).
inline Mesh quad_mesh(vec3 corner, vec3 eu, vec3 ev) {
  Mesh m;
  vec3 n = glm::normalize(glm::cross(eu, ev));
  m.positions = {corner, corner + eu, corner + eu + ev, corner + ev};
  m.normals = {n, n, n, n};
  m.uvs = {vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 1)};
  m.triangles = {uvec3(0, 1, 2), uvec3(0, 2, 3)};
  return m;
}

// UV sphere with every vertex exactly on the sphere; outward counter-clockwise triangles.
inline Mesh sphere_mesh(vec3 center, float radius, int segments, int rings) {
  Mesh m;
  for (int r = 0; r <= rings; ++r) {
    double theta = M_PI * r / rings;
    for (int s = 0; s <= segments; ++s) {
      double phi = 2.0 * M_PI * s / segments;
      vec3 n(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
             float(-std::sin(theta) * std::sin(phi)));
      m.positions.push_back(center + radius * n);
      m.normals.push_back(n);
      m.uvs.push_back(vec2(float(s) / segments, 1.0f - float(r) / rings));
    }
  }
  auto id = [&](int r, int s) { return uint32_t(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      if (r != 0) m.triangles.push_back(uvec3(id(r, s), id(r + 1, s), id(r, s + 1)));
      if (r != rings - 1) m.triangles.push_back(uvec3(id(r, s + 1), id(r + 1, s), id(r + 1, s + 1)));
    }
  return m;
}

inline uint32_t add_diffuse(Scene& scene, vec3 albedo, float specular = 0.0f, float gloss = 0.0f,
                            vec3 emission = vec3(0.0f)) {
  Material m;
  m.diffuse = albedo;
  m.specular = specular;
  m.gloss = gloss;
  m.emission = emission;
  return add_material(scene, m);
}

}  // namespace proxima::test
