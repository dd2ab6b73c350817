// Hand-built visibility inputs: each mesh its own object (its own vertices, no welding), as
// a level editor writes brushes.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "proxima/scene/scene.h"

namespace proxima::visibility {

inline void add_mesh(Scene& s, std::vector<vec3> positions, std::vector<uvec3> triangles) {
  Mesh mesh;
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  add_object(s, mesh, "o" + std::to_string(s.objects.size()), 0);
}

// Quad c, c + u, c + u + v, c + v, wound to face `toward` (single-sided, open).
inline void add_quad(Scene& s, vec3 c, vec3 u, vec3 v, vec3 toward) {
  if (glm::dot(glm::cross(u, v), toward - c) < 0.0f) std::swap(u, v);
  add_mesh(s, {c, c + u, c + u + v, c + v}, {{0, 1, 2}, {0, 2, 3}});
}

}  // namespace proxima::visibility
