// The thesis' Figure 11 scene (ch. 2), in x–z with slabs 2 m tall: two viewpoints
// V_0 = (−1, 0, 10), V_1 = (1, 0, 10) look down −Z at the origin.
//  - D: back wall at z = −2, visible from both.
//  - C: small box at the origin; hidden from V_0 behind B and A (doubly occluded), from
//    V_1 behind A; partly visible from the midpoint (an intermediate view).
//  - B: slab at z = 2, x ∈ [−0.4, −0.02]; hidden from V_0 behind A, visible from V_1.
//  - A: two slabs at z = 5 (x ∈ [−0.65, −0.35] and [0.35, 0.7]), visible from both.
// So conventional images capture A, B, D but not C; NRR's I_1 sees C through A (redundant
// with I_0); depth peeling from V_0 needs a third layer for C.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

#include "proxima/depthimage/view_set.h"
#include "proxima/scene/procedural.h"
#include "proxima/scene/scene.h"

namespace proxima::figure11 {

inline constexpr uint32_t kA = 0, kB = 1, kC = 2, kD = 3;  // object ids

inline Scene scene() {
  Scene s;
  s.name = "figure11";
  const uint32_t mat = add_material(s, Material{});
  auto slab = [](float x0, float x1, float z, float depth) {
    Mesh m = make_box(vec3(x1 - x0, 2.0f, depth), 2);
    transform_mesh(m, glm::translate(mat4(1.0f), vec3(0.5f * (x0 + x1), 0.0f, z)));
    return m;
  };
  Mesh a = slab(-0.65f, -0.35f, 5.0f, 0.05f);
  append_mesh(a, slab(0.35f, 0.7f, 5.0f, 0.05f));
  add_object(s, a, "A", mat);
  add_object(s, slab(-0.4f, -0.02f, 2.0f, 0.05f), "B", mat);
  add_object(s, slab(-0.2f, 0.2f, 0.0f, 0.4f), "C", mat);
  add_object(s, slab(-3.0f, 3.0f, -2.0f, 0.1f), "D", mat);
  s.point_lights.push_back(PointLight{vec3(0.0f, 3.0f, 8.0f), vec3(50.0f)});
  return s;
}

inline ViewSet views(int size) {
  const Camera base = look_at(vec3(0.0f, 0.0f, 10.0f), vec3(0.0f), vec3(0, 1, 0), 30.0f, size, size, 0.1f, 100.0f);
  return make_view_set(ViewShape::Segment, base, 1.0f, 10.0f);
}

}  // namespace proxima::figure11
