// Small scenes for the reflect/ tests: axis-aligned rooms and walls from single quads.
#pragma once

#include <string>

#include "proxima/scene/scene.h"

namespace proxima::reflect_test {

// Two-triangle quad corner + a·eu + b·ev facing cross(eu, ev), as one object.
inline uint32_t add_quad(Scene& s, vec3 corner, vec3 eu, vec3 ev, uint32_t material,
                         const std::string& name) {
  Mesh m;
  m.positions = {corner, corner + eu, corner + eu + ev, corner + ev};
  vec3 n = glm::normalize(glm::cross(eu, ev));
  m.normals.assign(4, n);
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return add_object(s, m, name, material);
}

inline uint32_t add_diffuse(Scene& s, vec3 color, float specular = 0.0f) {
  Material m;
  m.name = std::to_string(s.materials.size());
  m.diffuse = color;
  m.specular = specular;
  return add_material(s, m);
}

// Inward-facing box [lo, hi], one object and one color per wall (−X, +X, −Y, +Y, −Z, +Z),
// lit by a point light at its center and ambient light.
inline Scene box_room(vec3 lo, vec3 hi) {
  Scene s;
  s.name = "box";
  const vec3 colors[6] = {{0.8f, 0.2f, 0.2f}, {0.2f, 0.8f, 0.2f}, {0.2f, 0.2f, 0.8f},
                          {0.8f, 0.8f, 0.2f}, {0.2f, 0.8f, 0.8f}, {0.8f, 0.2f, 0.8f}};
  uint32_t m[6];
  for (int i = 0; i < 6; ++i) m[i] = add_diffuse(s, colors[i]);
  const vec3 d = hi - lo;
  add_quad(s, lo, {0, d.y, 0}, {0, 0, d.z}, m[0], "wall_nx");
  add_quad(s, {hi.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}, m[1], "wall_px");
  add_quad(s, lo, {0, 0, d.z}, {d.x, 0, 0}, m[2], "floor");
  add_quad(s, {lo.x, hi.y, lo.z}, {d.x, 0, 0}, {0, 0, d.z}, m[3], "ceiling");
  add_quad(s, lo, {d.x, 0, 0}, {0, d.y, 0}, m[4], "wall_nz");
  add_quad(s, {lo.x, lo.y, hi.z}, {0, d.y, 0}, {d.x, 0, 0}, m[5], "wall_pz");
  s.point_lights.push_back({0.5f * (lo + hi), vec3(4.0f)});
  s.ambient = vec3(0.1f);
  return s;
}

}  // namespace proxima::reflect_test
