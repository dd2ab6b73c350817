// A scene for the depth-only rasterizers' tests: spheres of many tiny triangles, a torus, a
// wide plane through the near and far planes of the cameras looking at the origin, and a
// box far behind them.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

#include "proxima/scene/procedural.h"
#include "proxima/scene/scene.h"

namespace proxima::raster_test {

inline Scene clutter() {
  Scene s;
  const uint32_t mat = add_material(s, Material{});
  for (int i = 0; i < 5; ++i) {
    Mesh m = make_sphere(0.3f + 0.1f * float(i), 96, 48);
    transform_mesh(m, glm::translate(mat4(1.0f), vec3(float(i) * 0.5f - 1.0f, 0.2f * float(i), -float(i) * 0.4f)));
    add_object(s, m, "sphere", mat);
  }
  Mesh torus = make_torus(1.0f, 0.2f, 64, 32);
  transform_mesh(torus, glm::rotate(mat4(1.0f), 0.7f, vec3(1, 0, 0)));
  add_object(s, torus, "torus", mat);
  Mesh ground = make_plane(200.0f, 200.0f, 40, 40);
  transform_mesh(ground, glm::translate(mat4(1.0f), vec3(0, -0.8f, 0)));
  add_object(s, ground, "ground", mat);
  Mesh box = make_box(vec3(1.0f));
  transform_mesh(box, glm::translate(mat4(1.0f), vec3(0, 0, 40.0f)));
  add_object(s, box, "behind", mat);
  return s;
}

}  // namespace proxima::raster_test
