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
  std::string name = std::to_string(s.objects.size());
  name.insert(name.begin(), 'o');  // not "o" + …: GCC 12 warns falsely on that (-Wstringop-overflow)
  add_object(s, mesh, name, 0);
}

// Quad c, c + u, c + u + v, c + v, wound to face `toward` (single-sided, open).
inline void add_quad(Scene& s, vec3 c, vec3 u, vec3 v, vec3 toward) {
  if (glm::dot(glm::cross(u, v), toward - c) < 0.0f) std::swap(u, v);
  add_mesh(s, {c, c + u, c + u + v, c + v}, {{0, 1, 2}, {0, 2, 3}});
}

// An axis-aligned brush (closed box, faces outward, one object), as a level editor writes
// it: 8 corners, 12 triangles, no CSG against other brushes. `skip` drops one face
// (0..5 = −x, +x, −y, +y, −z, +z) to make an open mesh; `inward` turns the faces inward
// (a room around the eye).
inline void add_box(Scene& s, vec3 lo, vec3 hi, int skip = -1, bool inward = false) {
  std::vector<vec3> p;
  for (int i = 0; i < 8; ++i) p.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // Counter-clockwise seen from outside.
  const uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  std::vector<uvec3> tris;
  for (int f = 0; f < 6; ++f) {
    if (f == skip) continue;
    const uint32_t* q = quads[f];
    if (inward) {
      tris.push_back({q[0], q[2], q[1]});
      tris.push_back({q[0], q[3], q[2]});
    } else {
      tris.push_back({q[0], q[1], q[2]});
      tris.push_back({q[0], q[2], q[3]});
    }
  }
  add_mesh(s, std::move(p), std::move(tris));
}

}  // namespace proxima::visibility
