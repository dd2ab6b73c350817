// Procedural meshes: sphere, cylinder, torus, box, plane and the Utah teapot.
// The teapot is Martin Newell's 1975 data set (32 bicubic Bézier patches over 306 control
// points, Z up, as distributed by Crow, "The Origins of the Teapot", IEEE CG&A 7(1), 1987).
#include "proxima/scene/procedural.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

namespace proxima {
namespace {

constexpr float kTwoPi = 2.0f * kPi;

// Appends the two triangles of quad a-b-c-d (counter-clockwise seen from the front).
void add_quad(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
}

void add_vertex(Mesh& mesh, vec3 p, vec3 n, vec2 uv) {
  mesh.positions.push_back(p);
  mesh.normals.push_back(n);
  mesh.uvs.push_back(uv);
}

// Point on the unit circle in the XZ plane at parameter j of `segments`: angle 0 is +Z,
// increasing toward +X. Index `segments` wraps to 0 exactly, so seams weld by position.
vec2 circle(int j, int segments) {
  if (j % segments == 0) return {0.0f, 1.0f};
  float phi = kTwoPi * float(j) / float(segments);
  return {std::sin(phi), std::cos(phi)};
}

}  // namespace

Mesh make_sphere(float radius, int segments, int rings) {
  assert(segments >= 3 && rings >= 2);
  Mesh m;
  // Rows i = 0 (north pole) .. rings (south pole); columns j = 0 .. segments (seam
  // duplicated for the uvs). Pole rows hold one vertex per column so each pole triangle
  // gets its own u.
  for (int i = 0; i <= rings; ++i) {
    float theta = kPi * float(i) / float(rings);
    float y = i == 0 ? 1.0f : i == rings ? -1.0f : std::cos(theta);
    bool pole = i == 0 || i == rings;
    float s = pole ? 0.0f : std::sin(theta);
    for (int j = 0; j <= segments; ++j) {
      vec2 c = circle(j, segments);
      vec3 n{s * c.x, y, s * c.y};
      // A pole vertex serves one triangle: give it the u of that triangle's middle.
      float u = (float(j) + (pole && j < segments ? 0.5f : 0.0f)) / float(segments);
      add_vertex(m, radius * n, n, {u, 1.0f - float(i) / float(rings)});
    }
  }
  const uint32_t row = uint32_t(segments + 1);
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      // Seen from outside: a top-left, b top-right, c bottom-left, d bottom-right. In the
      // pole bands one of the two triangles would have two vertices at the pole.
      uint32_t a = uint32_t(i) * row + uint32_t(j), b = a + 1, c = a + row, d = c + 1;
      if (i != rings - 1) m.triangles.push_back({a, c, d});
      if (i != 0) m.triangles.push_back({a, d, b});
    }
  }
  return m;
}

Mesh make_superellipsoid(vec3 radii, float exponent, int segments, int rings) {
  assert(exponent > 0.0f && radii.x > 0.0f && radii.y > 0.0f && radii.z > 0.0f);
  Mesh m = make_sphere(1.0f, segments, rings);
  auto signed_pow = [](float x, float e) { return std::copysign(std::pow(std::abs(x), e), x); };
  for (size_t i = 0; i < m.positions.size(); ++i) {
    vec3 n = m.normals[i];
    vec3 p, g;
    for (int c = 0; c < 3; ++c) {
      p[c] = radii[c] * signed_pow(n[c], exponent);
      // ∇ of Σ|p_i/r_i|^(2/e) at p, up to a positive factor: sign(n_i)·|n_i|^(2−e) / r_i.
      g[c] = signed_pow(n[c], 2.0f - exponent) / radii[c];
    }
    m.positions[i] = p;
    m.normals[i] = glm::normalize(g);
  }
  return m;
}

Mesh make_cylinder(float radius, float height, int segments, int rings, bool capped) {
  assert(segments >= 3 && rings >= 1);
  Mesh m;
  // Side: rows i = 0 (y = 0) .. rings (y = height), columns j = 0 .. segments.
  const uint32_t row = uint32_t(segments + 1);
  for (int i = 0; i <= rings; ++i) {
    float y = i == rings ? height : height * float(i) / float(rings);
    for (int j = 0; j <= segments; ++j) {
      vec2 c = circle(j, segments);
      add_vertex(m, {radius * c.x, y, radius * c.y}, {c.x, 0.0f, c.y},
                 {float(j) / float(segments), float(i) / float(rings)});
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      // a bottom-left, b bottom-right, c top-right, d top-left seen from outside.
      uint32_t a = uint32_t(i) * row + uint32_t(j);
      add_quad(m, a, a + 1, a + 1 + row, a + row);
    }
  }
  if (!capped) return m;
  // Caps: a center vertex and a ring of their own (normals ±Y); ring positions repeat the
  // side's exactly so the mesh is closed once vertices are welded by position.
  for (int cap = 0; cap < 2; ++cap) {
    bool top = cap == 1;
    float y = top ? height : 0.0f;
    vec3 n{0.0f, top ? 1.0f : -1.0f, 0.0f};
    uint32_t center = uint32_t(m.positions.size());
    add_vertex(m, {0.0f, y, 0.0f}, n, {0.5f, 0.5f});
    for (int j = 0; j < segments; ++j) {
      vec2 c = circle(j, segments);
      add_vertex(m, {radius * c.x, y, radius * c.y}, n, {0.5f + 0.5f * c.x, 0.5f - 0.5f * c.y});
    }
    for (int j = 0; j < segments; ++j) {
      uint32_t p = center + 1 + uint32_t(j);
      uint32_t q = center + 1 + uint32_t((j + 1) % segments);
      // cross(p − center, q − center) points along +Y (the angle grows toward +X from +Z).
      if (top) {
        m.triangles.push_back({center, p, q});
      } else {
        m.triangles.push_back({center, q, p});
      }
    }
  }
  return m;
}

Mesh make_torus(float major_radius, float minor_radius, int major_segments, int minor_segments) {
  assert(major_segments >= 3 && minor_segments >= 3);
  Mesh m;
  // Rows i over the minor angle ψ (0 = outer equator, growing upward), columns j over the
  // major angle φ (0 = +Z, growing toward +X); both seams duplicated for the uvs.
  const uint32_t row = uint32_t(major_segments + 1);
  for (int i = 0; i <= minor_segments; ++i) {
    vec2 t = circle(i, minor_segments);  // (sin ψ, cos ψ)
    for (int j = 0; j <= major_segments; ++j) {
      vec2 c = circle(j, major_segments);
      vec3 radial{c.x, 0.0f, c.y};
      vec3 n = t.y * radial + vec3(0.0f, t.x, 0.0f);
      add_vertex(m, major_radius * radial + minor_radius * n, n,
                 {float(j) / float(major_segments), float(i) / float(minor_segments)});
    }
  }
  for (int i = 0; i < minor_segments; ++i) {
    for (int j = 0; j < major_segments; ++j) {
      uint32_t a = uint32_t(i) * row + uint32_t(j);
      add_quad(m, a, a + 1, a + 1 + row, a + row);
    }
  }
  return m;
}

Mesh make_box(vec3 size, int subdivisions) {
  assert(subdivisions >= 1);
  const int n = subdivisions;
  Mesh m;
  // Coordinate of grid line k (0..n) along axis `axis`; shared by the faces meeting at an
  // edge, so their vertices coincide bit for bit.
  auto coord = [&](int axis, int k) {
    return k == n ? 0.5f * size[axis] : -0.5f * size[axis] + size[axis] * float(k) / float(n);
  };
  // Each face: normal axis and sign, then its u and v axes (signed) with cross(u, v) = normal.
  struct Face {
    int axis, sign, u_axis, u_sign, v_axis, v_sign;
  };
  static constexpr std::array<Face, 6> kFaces = {{
      {0, +1, 2, -1, 1, +1},  // +X: u = −Z, v = +Y
      {0, -1, 2, +1, 1, +1},  // −X: u = +Z, v = +Y
      {1, +1, 0, +1, 2, -1},  // +Y: u = +X, v = −Z
      {1, -1, 0, +1, 2, +1},  // −Y: u = +X, v = +Z
      {2, +1, 0, +1, 1, +1},  // +Z: u = +X, v = +Y
      {2, -1, 0, -1, 1, +1},  // −Z: u = −X, v = +Y
  }};
  for (const Face& f : kFaces) {
    vec3 normal(0.0f);
    normal[f.axis] = float(f.sign);
    uint32_t base = uint32_t(m.positions.size());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        vec3 p;
        p[f.axis] = f.sign > 0 ? 0.5f * size[f.axis] : -0.5f * size[f.axis];
        p[f.u_axis] = coord(f.u_axis, f.u_sign > 0 ? i : n - i);
        p[f.v_axis] = coord(f.v_axis, f.v_sign > 0 ? j : n - j);
        add_vertex(m, p, normal, {float(i) / float(n), float(j) / float(n)});
      }
    }
    const uint32_t row = uint32_t(n + 1);
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        uint32_t a = base + uint32_t(j) * row + uint32_t(i);
        add_quad(m, a, a + 1, a + 1 + row, a + row);
      }
    }
  }
  return m;
}

Mesh make_plane(float size_x, float size_z, int n, int m_) {
  assert(n >= 1 && m_ >= 1);
  Mesh m;
  // u along +X, v along −Z, so cross(u, v) = +Y.
  for (int j = 0; j <= m_; ++j) {
    for (int i = 0; i <= n; ++i) {
      float u = float(i) / float(n), v = float(j) / float(m_);
      add_vertex(m, {size_x * (u - 0.5f), 0.0f, size_z * (0.5f - v)}, {0.0f, 1.0f, 0.0f}, {u, v});
    }
  }
  const uint32_t row = uint32_t(n + 1);
  for (int j = 0; j < m_; ++j) {
    for (int i = 0; i < n; ++i) {
      uint32_t a = uint32_t(j) * row + uint32_t(i);
      add_quad(m, a, a + 1, a + 1 + row, a + row);
    }
  }
  return m;
}

// ---- Utah teapot ---------------------------------------------------------------------

namespace {

// Newell's patches: 16 one-based indices into kTeapotPoints, row-major 4 × 4 (row r, column
// c). Rows 0–3 of patches 20–23 (lid knob) and 28–31 (bottom) start with one point repeated
// four times: that edge of the patch collapses to a pole. Order: rim 0–3, upper body 4–7,
// lower body 8–11, handle 12–15, spout 16–19, lid 20–27, bottom 28–31.
constexpr uint16_t kTeapotPatches[32][16] = {
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69},
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194},
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212},
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242},
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271},
};

// Newell's 306 control points (x, y, z), Z up, the lid knob's top at z = 3.15 and the
// bottom's pole at z = 0. Points 205, 206, 216 and 223 (the lid's 0.002 offsets) are part
// of the original set but no patch uses them.
constexpr float kTeapotPoints[306][3] = {
    {1.4f, 0.0f, 2.4f}, {1.4f, -0.784f, 2.4f}, {0.784f, -1.4f, 2.4f},
    {0.0f, -1.4f, 2.4f}, {1.3375f, 0.0f, 2.53125f}, {1.3375f, -0.749f, 2.53125f},
    {0.749f, -1.3375f, 2.53125f}, {0.0f, -1.3375f, 2.53125f}, {1.4375f, 0.0f, 2.53125f},
    {1.4375f, -0.805f, 2.53125f}, {0.805f, -1.4375f, 2.53125f}, {0.0f, -1.4375f, 2.53125f},
    {1.5f, 0.0f, 2.4f}, {1.5f, -0.84f, 2.4f}, {0.84f, -1.5f, 2.4f},
    {0.0f, -1.5f, 2.4f}, {-0.784f, -1.4f, 2.4f}, {-1.4f, -0.784f, 2.4f},
    {-1.4f, 0.0f, 2.4f}, {-0.749f, -1.3375f, 2.53125f}, {-1.3375f, -0.749f, 2.53125f},
    {-1.3375f, 0.0f, 2.53125f}, {-0.805f, -1.4375f, 2.53125f}, {-1.4375f, -0.805f, 2.53125f},
    {-1.4375f, 0.0f, 2.53125f}, {-0.84f, -1.5f, 2.4f}, {-1.5f, -0.84f, 2.4f},
    {-1.5f, 0.0f, 2.4f}, {-1.4f, 0.784f, 2.4f}, {-0.784f, 1.4f, 2.4f},
    {0.0f, 1.4f, 2.4f}, {-1.3375f, 0.749f, 2.53125f}, {-0.749f, 1.3375f, 2.53125f},
    {0.0f, 1.3375f, 2.53125f}, {-1.4375f, 0.805f, 2.53125f}, {-0.805f, 1.4375f, 2.53125f},
    {0.0f, 1.4375f, 2.53125f}, {-1.5f, 0.84f, 2.4f}, {-0.84f, 1.5f, 2.4f},
    {0.0f, 1.5f, 2.4f}, {0.784f, 1.4f, 2.4f}, {1.4f, 0.784f, 2.4f},
    {0.749f, 1.3375f, 2.53125f}, {1.3375f, 0.749f, 2.53125f}, {0.805f, 1.4375f, 2.53125f},
    {1.4375f, 0.805f, 2.53125f}, {0.84f, 1.5f, 2.4f}, {1.5f, 0.84f, 2.4f},
    {1.75f, 0.0f, 1.875f}, {1.75f, -0.98f, 1.875f}, {0.98f, -1.75f, 1.875f},
    {0.0f, -1.75f, 1.875f}, {2.0f, 0.0f, 1.35f}, {2.0f, -1.12f, 1.35f},
    {1.12f, -2.0f, 1.35f}, {0.0f, -2.0f, 1.35f}, {2.0f, 0.0f, 0.9f},
    {2.0f, -1.12f, 0.9f}, {1.12f, -2.0f, 0.9f}, {0.0f, -2.0f, 0.9f},
    {-0.98f, -1.75f, 1.875f}, {-1.75f, -0.98f, 1.875f}, {-1.75f, 0.0f, 1.875f},
    {-1.12f, -2.0f, 1.35f}, {-2.0f, -1.12f, 1.35f}, {-2.0f, 0.0f, 1.35f},
    {-1.12f, -2.0f, 0.9f}, {-2.0f, -1.12f, 0.9f}, {-2.0f, 0.0f, 0.9f},
    {-1.75f, 0.98f, 1.875f}, {-0.98f, 1.75f, 1.875f}, {0.0f, 1.75f, 1.875f},
    {-2.0f, 1.12f, 1.35f}, {-1.12f, 2.0f, 1.35f}, {0.0f, 2.0f, 1.35f},
    {-2.0f, 1.12f, 0.9f}, {-1.12f, 2.0f, 0.9f}, {0.0f, 2.0f, 0.9f},
    {0.98f, 1.75f, 1.875f}, {1.75f, 0.98f, 1.875f}, {1.12f, 2.0f, 1.35f},
    {2.0f, 1.12f, 1.35f}, {1.12f, 2.0f, 0.9f}, {2.0f, 1.12f, 0.9f},
    {2.0f, 0.0f, 0.45f}, {2.0f, -1.12f, 0.45f}, {1.12f, -2.0f, 0.45f},
    {0.0f, -2.0f, 0.45f}, {1.5f, 0.0f, 0.225f}, {1.5f, -0.84f, 0.225f},
    {0.84f, -1.5f, 0.225f}, {0.0f, -1.5f, 0.225f}, {1.5f, 0.0f, 0.15f},
    {1.5f, -0.84f, 0.15f}, {0.84f, -1.5f, 0.15f}, {0.0f, -1.5f, 0.15f},
    {-1.12f, -2.0f, 0.45f}, {-2.0f, -1.12f, 0.45f}, {-2.0f, 0.0f, 0.45f},
    {-0.84f, -1.5f, 0.225f}, {-1.5f, -0.84f, 0.225f}, {-1.5f, 0.0f, 0.225f},
    {-0.84f, -1.5f, 0.15f}, {-1.5f, -0.84f, 0.15f}, {-1.5f, 0.0f, 0.15f},
    {-2.0f, 1.12f, 0.45f}, {-1.12f, 2.0f, 0.45f}, {0.0f, 2.0f, 0.45f},
    {-1.5f, 0.84f, 0.225f}, {-0.84f, 1.5f, 0.225f}, {0.0f, 1.5f, 0.225f},
    {-1.5f, 0.84f, 0.15f}, {-0.84f, 1.5f, 0.15f}, {0.0f, 1.5f, 0.15f},
    {1.12f, 2.0f, 0.45f}, {2.0f, 1.12f, 0.45f}, {0.84f, 1.5f, 0.225f},
    {1.5f, 0.84f, 0.225f}, {0.84f, 1.5f, 0.15f}, {1.5f, 0.84f, 0.15f},
    {-1.6f, 0.0f, 2.025f}, {-1.6f, -0.3f, 2.025f}, {-1.5f, -0.3f, 2.25f},
    {-1.5f, 0.0f, 2.25f}, {-2.3f, 0.0f, 2.025f}, {-2.3f, -0.3f, 2.025f},
    {-2.5f, -0.3f, 2.25f}, {-2.5f, 0.0f, 2.25f}, {-2.7f, 0.0f, 2.025f},
    {-2.7f, -0.3f, 2.025f}, {-3.0f, -0.3f, 2.25f}, {-3.0f, 0.0f, 2.25f},
    {-2.7f, 0.0f, 1.8f}, {-2.7f, -0.3f, 1.8f}, {-3.0f, -0.3f, 1.8f},
    {-3.0f, 0.0f, 1.8f}, {-1.5f, 0.3f, 2.25f}, {-1.6f, 0.3f, 2.025f},
    {-2.5f, 0.3f, 2.25f}, {-2.3f, 0.3f, 2.025f}, {-3.0f, 0.3f, 2.25f},
    {-2.7f, 0.3f, 2.025f}, {-3.0f, 0.3f, 1.8f}, {-2.7f, 0.3f, 1.8f},
    {-2.7f, 0.0f, 1.575f}, {-2.7f, -0.3f, 1.575f}, {-3.0f, -0.3f, 1.35f},
    {-3.0f, 0.0f, 1.35f}, {-2.5f, 0.0f, 1.125f}, {-2.5f, -0.3f, 1.125f},
    {-2.65f, -0.3f, 0.9375f}, {-2.65f, 0.0f, 0.9375f}, {-2.0f, -0.3f, 0.9f},
    {-1.9f, -0.3f, 0.6f}, {-1.9f, 0.0f, 0.6f}, {-3.0f, 0.3f, 1.35f},
    {-2.7f, 0.3f, 1.575f}, {-2.65f, 0.3f, 0.9375f}, {-2.5f, 0.3f, 1.125f},
    {-1.9f, 0.3f, 0.6f}, {-2.0f, 0.3f, 0.9f}, {1.7f, 0.0f, 1.425f},
    {1.7f, -0.66f, 1.425f}, {1.7f, -0.66f, 0.6f}, {1.7f, 0.0f, 0.6f},
    {2.6f, 0.0f, 1.425f}, {2.6f, -0.66f, 1.425f}, {3.1f, -0.66f, 0.825f},
    {3.1f, 0.0f, 0.825f}, {2.3f, 0.0f, 2.1f}, {2.3f, -0.25f, 2.1f},
    {2.4f, -0.25f, 2.025f}, {2.4f, 0.0f, 2.025f}, {2.7f, 0.0f, 2.4f},
    {2.7f, -0.25f, 2.4f}, {3.3f, -0.25f, 2.4f}, {3.3f, 0.0f, 2.4f},
    {1.7f, 0.66f, 0.6f}, {1.7f, 0.66f, 1.425f}, {3.1f, 0.66f, 0.825f},
    {2.6f, 0.66f, 1.425f}, {2.4f, 0.25f, 2.025f}, {2.3f, 0.25f, 2.1f},
    {3.3f, 0.25f, 2.4f}, {2.7f, 0.25f, 2.4f}, {2.8f, 0.0f, 2.475f},
    {2.8f, -0.25f, 2.475f}, {3.525f, -0.25f, 2.49375f}, {3.525f, 0.0f, 2.49375f},
    {2.9f, 0.0f, 2.475f}, {2.9f, -0.15f, 2.475f}, {3.45f, -0.15f, 2.5125f},
    {3.45f, 0.0f, 2.5125f}, {2.8f, 0.0f, 2.4f}, {2.8f, -0.15f, 2.4f},
    {3.2f, -0.15f, 2.4f}, {3.2f, 0.0f, 2.4f}, {3.525f, 0.25f, 2.49375f},
    {2.8f, 0.25f, 2.475f}, {3.45f, 0.15f, 2.5125f}, {2.9f, 0.15f, 2.475f},
    {3.2f, 0.15f, 2.4f}, {2.8f, 0.15f, 2.4f}, {0.0f, 0.0f, 3.15f},
    {0.0f, -0.002f, 3.15f}, {0.002f, 0.0f, 3.15f}, {0.8f, 0.0f, 3.15f},
    {0.8f, -0.45f, 3.15f}, {0.45f, -0.8f, 3.15f}, {0.0f, -0.8f, 3.15f},
    {0.0f, 0.0f, 2.85f}, {0.2f, 0.0f, 2.7f}, {0.2f, -0.112f, 2.7f},
    {0.112f, -0.2f, 2.7f}, {0.0f, -0.2f, 2.7f}, {-0.002f, 0.0f, 3.15f},
    {-0.45f, -0.8f, 3.15f}, {-0.8f, -0.45f, 3.15f}, {-0.8f, 0.0f, 3.15f},
    {-0.112f, -0.2f, 2.7f}, {-0.2f, -0.112f, 2.7f}, {-0.2f, 0.0f, 2.7f},
    {0.0f, 0.002f, 3.15f}, {-0.8f, 0.45f, 3.15f}, {-0.45f, 0.8f, 3.15f},
    {0.0f, 0.8f, 3.15f}, {-0.2f, 0.112f, 2.7f}, {-0.112f, 0.2f, 2.7f},
    {0.0f, 0.2f, 2.7f}, {0.45f, 0.8f, 3.15f}, {0.8f, 0.45f, 3.15f},
    {0.112f, 0.2f, 2.7f}, {0.2f, 0.112f, 2.7f}, {0.4f, 0.0f, 2.55f},
    {0.4f, -0.224f, 2.55f}, {0.224f, -0.4f, 2.55f}, {0.0f, -0.4f, 2.55f},
    {1.3f, 0.0f, 2.55f}, {1.3f, -0.728f, 2.55f}, {0.728f, -1.3f, 2.55f},
    {0.0f, -1.3f, 2.55f}, {1.3f, 0.0f, 2.4f}, {1.3f, -0.728f, 2.4f},
    {0.728f, -1.3f, 2.4f}, {0.0f, -1.3f, 2.4f}, {-0.224f, -0.4f, 2.55f},
    {-0.4f, -0.224f, 2.55f}, {-0.4f, 0.0f, 2.55f}, {-0.728f, -1.3f, 2.55f},
    {-1.3f, -0.728f, 2.55f}, {-1.3f, 0.0f, 2.55f}, {-0.728f, -1.3f, 2.4f},
    {-1.3f, -0.728f, 2.4f}, {-1.3f, 0.0f, 2.4f}, {-0.4f, 0.224f, 2.55f},
    {-0.224f, 0.4f, 2.55f}, {0.0f, 0.4f, 2.55f}, {-1.3f, 0.728f, 2.55f},
    {-0.728f, 1.3f, 2.55f}, {0.0f, 1.3f, 2.55f}, {-1.3f, 0.728f, 2.4f},
    {-0.728f, 1.3f, 2.4f}, {0.0f, 1.3f, 2.4f}, {0.224f, 0.4f, 2.55f},
    {0.4f, 0.224f, 2.55f}, {0.728f, 1.3f, 2.55f}, {1.3f, 0.728f, 2.55f},
    {0.728f, 1.3f, 2.4f}, {1.3f, 0.728f, 2.4f}, {0.0f, 0.0f, 0.0f},
    {1.5f, 0.0f, 0.15f}, {1.5f, 0.84f, 0.15f}, {0.84f, 1.5f, 0.15f},
    {0.0f, 1.5f, 0.15f}, {1.5f, 0.0f, 0.075f}, {1.5f, 0.84f, 0.075f},
    {0.84f, 1.5f, 0.075f}, {0.0f, 1.5f, 0.075f}, {1.425f, 0.0f, 0.0f},
    {1.425f, 0.798f, 0.0f}, {0.798f, 1.425f, 0.0f}, {0.0f, 1.425f, 0.0f},
    {-0.84f, 1.5f, 0.15f}, {-1.5f, 0.84f, 0.15f}, {-1.5f, 0.0f, 0.15f},
    {-0.84f, 1.5f, 0.075f}, {-1.5f, 0.84f, 0.075f}, {-1.5f, 0.0f, 0.075f},
    {-0.798f, 1.425f, 0.0f}, {-1.425f, 0.798f, 0.0f}, {-1.425f, 0.0f, 0.0f},
    {-1.5f, -0.84f, 0.15f}, {-0.84f, -1.5f, 0.15f}, {0.0f, -1.5f, 0.15f},
    {-1.5f, -0.84f, 0.075f}, {-0.84f, -1.5f, 0.075f}, {0.0f, -1.5f, 0.075f},
    {-1.425f, -0.798f, 0.0f}, {-0.798f, -1.425f, 0.0f}, {0.0f, -1.425f, 0.0f},
    {0.84f, -1.5f, 0.15f}, {1.5f, -0.84f, 0.15f}, {0.84f, -1.5f, 0.075f},
    {1.5f, -0.84f, 0.075f}, {0.798f, -1.425f, 0.0f}, {1.425f, -0.798f, 0.0f},
};

constexpr float kTeapotHeight = 3.15f;  // z of the lid knob's pole; the bottom's is 0

// Cubic Bernstein weights and their derivatives at t.
void bernstein(float t, float b[4], float db[4]) {
  float s = 1.0f - t;
  b[0] = s * s * s;
  b[1] = 3.0f * t * s * s;
  b[2] = 3.0f * t * t * s;
  b[3] = t * t * t;
  db[0] = -3.0f * s * s;
  db[1] = 3.0f * s * s - 6.0f * t * s;
  db[2] = 6.0f * t * s - 3.0f * t * t;
  db[3] = 3.0f * t * t;
}

struct PatchSample {
  vec3 p, dp_du, dp_dv;
};

// Patch point and partial derivatives at (u, v); u runs over rows, v over columns.
PatchSample eval_patch(const std::array<vec3, 16>& cp, float u, float v) {
  float bu[4], dbu[4], bv[4], dbv[4];
  bernstein(u, bu, dbu);
  bernstein(v, bv, dbv);
  PatchSample s{vec3(0.0f), vec3(0.0f), vec3(0.0f)};
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      const vec3& q = cp[size_t(r * 4 + c)];
      s.p += bu[r] * bv[c] * q;
      s.dp_du += dbu[r] * bv[c] * q;
      s.dp_dv += bu[r] * dbv[c] * q;
    }
  }
  return s;
}

}  // namespace

Mesh make_teapot(int tessellation) {
  assert(tessellation >= 1);
  const int n = tessellation;
  // Newell's Z-up frame → ours (Y up, spout toward +X): (x, y, z) → (x, z, −y), then scaled
  // to height 1. This is a rotation, so the patches' orientation is kept: with u down the
  // rows and v along the columns, cross(∂p/∂v, ∂p/∂u) points out of the pot.
  const float scale = 1.0f / kTeapotHeight;
  auto to_world = [&](const float* q) { return scale * vec3(q[0], q[2], -q[1]); };
  Mesh m;
  std::vector<uint32_t> rim;  // vertices on a patch boundary
  for (const auto& patch : kTeapotPatches) {
    std::array<vec3, 16> cp;
    for (size_t i = 0; i < 16; ++i) cp[i] = to_world(kTeapotPoints[patch[i] - 1]);
    // Row 0 collapsed to one point (the lid's and the bottom's poles).
    const bool pole = patch[0] == patch[1] && patch[1] == patch[2] && patch[2] == patch[3];
    const uint32_t base = uint32_t(m.positions.size());
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        float u = float(i) / float(n), v = float(j) / float(n);
        PatchSample s = eval_patch(cp, u, v);
        vec3 normal = glm::cross(s.dp_dv, s.dp_du);
        if (i == 0 && pole) {
          // ∂p/∂v vanishes at the pole; use the limit of the normal as u → 0 along the
          // column, and the exact pole position so the pole's triangles share it.
          PatchSample near = eval_patch(cp, 1e-3f, v);
          normal = glm::cross(near.dp_dv, near.dp_du);
          s.p = cp[0];
        }
        if (i == 0 || i == n || j == 0 || j == n) rim.push_back(uint32_t(m.positions.size()));
        add_vertex(m, s.p, glm::normalize(normal), {v, 1.0f - u});
      }
    }
    const uint32_t row = uint32_t(n + 1);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        // a = (u_i, v_j), b = (u_i, v_j+1), c = (u_i+1, v_j+1), d = (u_i+1, v_j): triangle
        // a-b-c has normal (b − a) × (c − a) ∝ ∂v × (∂u + ∂v) = ∂v × ∂u, outward.
        uint32_t a = base + uint32_t(i) * row + uint32_t(j), b = a + 1, c = b + row, d = a + row;
        if (i == 0 && pole) {
          m.triangles.push_back({a, c, d});  // a and b are the same pole point
        } else {
          add_quad(m, a, b, c, d);
        }
      }
    }
  }
  // Neighbouring patches evaluate their shared edge from differently ordered control points
  // (the bottom's run opposite to the body's), so shared points can differ in the last bits.
  // Snap them to one position so the surface has no cracks.
  std::sort(rim.begin(), rim.end(),
            [&](uint32_t x, uint32_t y) { return m.positions[x].x < m.positions[y].x; });
  constexpr float kSnap = 1e-6f;
  for (size_t k = 0; k < rim.size(); ++k) {
    const vec3 p = m.positions[rim[k]];
    for (size_t l = k + 1; l < rim.size() && m.positions[rim[l]].x - p.x <= kSnap; ++l) {
      vec3& q = m.positions[rim[l]];
      if (glm::all(glm::lessThanEqual(glm::abs(q - p), vec3(kSnap)))) q = p;
    }
  }
  return m;
}

}  // namespace proxima
