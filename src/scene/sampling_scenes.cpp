// Procedural scenes of thesis ch. 2 (sampling_scenes.h): nest, grass, city, tree. The
// thesis' models are not available; these match their triangle counts and kind of
// occlusion (interwoven thin twigs, dense blades, box canyons, foliage).
#include "proxima/scene/sampling_scenes.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/rng.h"
#include "proxima/scene/procedural.h"

namespace proxima {
namespace {

// Uniform in [lo, hi).
float uniform(Pcg32& rng, float lo, float hi) { return lo + (hi - lo) * rng.next_float(); }

// Any unit vector orthogonal to the unit vector d.
vec3 orthogonal(vec3 d) {
  const vec3 a = std::abs(d.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
  return glm::normalize(glm::cross(d, a));
}

// Open tube from a (radius ra) to b (radius rb) with `sides` sides: 2·sides triangles,
// facing outward.
void add_tube(Mesh& m, vec3 a, vec3 b, float ra, float rb, int sides) {
  const vec3 axis = glm::normalize(b - a);
  const vec3 u = orthogonal(axis), v = glm::cross(axis, u);
  const uint32_t base = uint32_t(m.positions.size());
  for (int end = 0; end < 2; ++end) {
    for (int j = 0; j < sides; ++j) {
      const float phi = 2.0f * kPi * float(j) / float(sides);
      const vec3 n = std::cos(phi) * u + std::sin(phi) * v;
      m.positions.push_back((end ? b : a) + (end ? rb : ra) * n);
      m.normals.push_back(n);
      m.uvs.push_back({float(j) / float(sides), float(end)});
    }
  }
  const uint32_t s = uint32_t(sides);
  for (uint32_t j = 0; j < s; ++j) {
    const uint32_t k = (j + 1) % s;
    // (u, v, axis) is right-handed, so a0 → a1 → b1 is counter-clockwise from outside.
    m.triangles.push_back({base + j, base + k, base + s + k});
    m.triangles.push_back({base + j, base + s + k, base + s + j});
  }
}

// Back sides for the triangles added to `m` since vertex `first_vertex` / triangle
// `first_triangle`: copies with the opposite winding and flipped normals, moved 1 mm
// along the back normal, so that front and back never tie in depth (a tie would be
// broken by triangle id in the rasterizer and arbitrarily by Embree).
constexpr float kBackOffset = 1e-3f;  // meters

void make_double_sided(Mesh& m, uint32_t first_vertex, uint32_t first_triangle) {
  const uint32_t vertices = uint32_t(m.positions.size()), triangles = uint32_t(m.triangles.size());
  const uint32_t offset = vertices - first_vertex;
  for (uint32_t i = first_vertex; i < vertices; ++i) {
    m.positions.push_back(m.positions[i] - kBackOffset * m.normals[i]);
    m.normals.push_back(-m.normals[i]);
    m.uvs.push_back(m.uvs[i]);
  }
  for (uint32_t t = first_triangle; t < triangles; ++t) {
    const uvec3 tri = m.triangles[t];
    m.triangles.push_back({tri.x + offset, tri.z + offset, tri.y + offset});
  }
}

Material diffuse(const char* name, vec3 color) {
  Material m;
  m.name = name;
  m.diffuse = color;
  return m;
}

void finish(Scene& s, vec3 eye, vec3 target, float vfov, vec3 light, float intensity) {
  s.ambient = vec3(0.15f);
  s.point_lights.push_back(PointLight{light, vec3(intensity)});
  NamedCamera cam;
  cam.name = "main";
  cam.camera = look_at(eye, target, vec3(0, 1, 0), vfov, 512, 512, 0.01f, 200.0f);
  s.cameras.push_back(cam);
}

Mesh ground(float size) {
  Mesh g = make_plane(size, size, 1, 1);
  return g;
}

}  // namespace

Scene make_nest_scene() {
  Scene s;
  s.name = "nest";
  Pcg32 rng(derive_seed(0x6e657374u, 1));
  Mesh twigs;
  // Twig centres on a bowl: the lower half of a sphere of radius 1 (centre at y = 1) and
  // a rim; directions tangent to the sphere, so twigs weave around the bowl.
  for (int i = 0; i < 5580; ++i) {
    const float phi = uniform(rng, 0.0f, 2.0f * kPi);
    const float cos_theta = uniform(rng, -1.0f, 0.15f);  // mostly below the equator
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const float r = uniform(rng, 0.85f, 1.05f);
    const vec3 n(sin_theta * std::cos(phi), cos_theta, sin_theta * std::sin(phi));
    const vec3 c = vec3(0, 1, 0) + r * n;
    const vec3 t0 = orthogonal(n), t1 = glm::cross(n, t0);
    const float a = uniform(rng, 0.0f, 2.0f * kPi);
    const vec3 dir = glm::normalize(std::cos(a) * t0 + std::sin(a) * t1 + uniform(rng, -0.2f, 0.2f) * n);
    const float half = 0.5f * uniform(rng, 0.25f, 0.6f);
    const float radius = uniform(rng, 0.006f, 0.014f);
    add_tube(twigs, c - half * dir, c + half * dir, radius, 0.6f * radius, 6);
  }
  add_object(s, twigs, "twigs", add_material(s, diffuse("twig", {0.45f, 0.32f, 0.18f})));
  add_object(s, ground(8.0f), "ground", add_material(s, diffuse("ground", {0.3f, 0.35f, 0.2f})));
  finish(s, {0.0f, 3.2f, 2.6f}, {0.0f, 0.6f, 0.0f}, 45.0f, {1.5f, 5.0f, 2.0f}, 60.0f);
  return s;
}

Scene make_grass_scene(int blade_count) {
  Scene s;
  s.name = "grass";
  Pcg32 rng(derive_seed(0x67726173u, 1));
  Mesh blades;
  constexpr int kSegments = 3;  // per blade side: 2·kSegments triangles
  for (int i = 0; i < blade_count; ++i) {
    const uint32_t first_vertex = uint32_t(blades.positions.size());
    const uint32_t first_triangle = uint32_t(blades.triangles.size());
    const vec3 root(uniform(rng, -2.0f, 2.0f), 0.0f, uniform(rng, -2.0f, 2.0f));
    const float yaw = uniform(rng, 0.0f, 2.0f * kPi);
    const vec3 side(std::cos(yaw), 0.0f, std::sin(yaw));   // across the blade
    const vec3 lean(-side.z, 0.0f, side.x);                // the way it bends
    const float height = uniform(rng, 0.2f, 0.6f), width = uniform(rng, 0.02f, 0.04f);
    const float bend = uniform(rng, 0.1f, 0.5f);
    for (int k = 0; k <= kSegments; ++k) {
      const float t = float(k) / float(kSegments);
      const vec3 p = root + height * (t * vec3(0, 1, 0) + bend * t * t * lean);
      const vec3 tangent = glm::normalize(vec3(0, 1, 0) + 2.0f * bend * t * lean);
      const vec3 n = glm::normalize(glm::cross(side, tangent));
      const float w = 0.5f * width * (1.0f - 0.9f * t);
      for (float sgn : {-1.0f, 1.0f}) {
        blades.positions.push_back(p + sgn * w * side);
        blades.normals.push_back(n);
        blades.uvs.push_back({0.5f + 0.5f * sgn, t});
      }
    }
    for (uint32_t k = 0; k < kSegments; ++k) {
      const uint32_t a = first_vertex + 2 * k;
      blades.triangles.push_back({a, a + 1, a + 3});
      blades.triangles.push_back({a, a + 3, a + 2});
    }
    make_double_sided(blades, first_vertex, first_triangle);
  }
  add_object(s, blades, "blades", add_material(s, diffuse("blade", {0.2f, 0.55f, 0.15f})));
  add_object(s, ground(6.0f), "ground", add_material(s, diffuse("soil", {0.35f, 0.25f, 0.15f})));
  finish(s, {0.0f, 1.4f, 3.2f}, {0.0f, 0.1f, 0.0f}, 50.0f, {2.0f, 6.0f, 3.0f}, 80.0f);
  return s;
}

Scene make_city_scene() {
  Scene s;
  s.name = "city";
  Pcg32 rng(derive_seed(0x63697479u, 1));
  Mesh buildings;
  constexpr int kGrid = 64;
  constexpr float kLot = 1.4f;  // 1 m building footprint + 0.4 m street
  for (int j = 0; j < kGrid; ++j) {
    for (int i = 0; i < kGrid; ++i) {
      const float h = 0.5f + 5.5f * std::pow(rng.next_float(), 2.0f);  // mostly low, a few towers
      const float w = uniform(rng, 0.7f, 1.0f), d = uniform(rng, 0.7f, 1.0f);
      Mesh box = make_box({w, h, d}, 1);
      const vec3 at((float(i) - 0.5f * float(kGrid - 1)) * kLot, 0.5f * h, (float(j) - 0.5f * float(kGrid - 1)) * kLot);
      transform_mesh(box, glm::translate(mat4(1.0f), at));
      append_mesh(buildings, box);
    }
  }
  add_object(s, buildings, "buildings", add_material(s, diffuse("concrete", {0.6f, 0.58f, 0.55f})));
  add_object(s, ground(kGrid * kLot + 10.0f), "ground", add_material(s, diffuse("asphalt", vec3(0.25f))));
  finish(s, {0.0f, 25.0f, 60.0f}, {0.0f, 0.0f, 5.0f}, 60.0f, {30.0f, 80.0f, 50.0f}, 9000.0f);
  return s;
}

namespace {

struct TreeBuilder {
  Pcg32 rng{derive_seed(0x74726565u, 1)};
  Mesh wood, leaves;

  // Branch from `base` along `dir`; depth 0 is a twig that carries leaves.
  void branch(vec3 base, vec3 dir, float length, float radius, int depth) {
    const vec3 tip = base + length * dir;
    add_tube(wood, base, tip, radius, 0.7f * radius, 8);
    if (depth == 0) {
      for (int k = 0; k < 110; ++k) leaf(base + uniform(rng, 0.1f, 1.0f) * (tip - base), dir);
      return;
    }
    const int children = 3;
    for (int c = 0; c < children; ++c) {
      const vec3 u = orthogonal(dir), v = glm::cross(dir, u);
      const float a = 2.0f * kPi * (float(c) + uniform(rng, 0.0f, 0.5f)) / float(children);
      const float spread = uniform(rng, 0.5f, 0.9f);
      const vec3 child = glm::normalize(dir + spread * (std::cos(a) * u + std::sin(a) * v) + vec3(0, 0.15f, 0));
      const vec3 at = base + uniform(rng, 0.55f, 1.0f) * (tip - base);
      branch(at, child, 0.72f * length, 0.65f * radius, depth - 1);
    }
  }

  // A double-sided leaf quad (4 triangles) near `p`.
  void leaf(vec3 p, vec3 dir) {
    const uint32_t first_vertex = uint32_t(leaves.positions.size());
    const uint32_t first_triangle = uint32_t(leaves.triangles.size());
    const vec3 offset(uniform(rng, -0.12f, 0.12f), uniform(rng, -0.12f, 0.12f), uniform(rng, -0.12f, 0.12f));
    const vec3 c = p + offset;
    const vec3 a = glm::normalize(dir + vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)));
    const vec3 b = orthogonal(a);
    const vec3 n = glm::cross(a, b);
    const float len = uniform(rng, 0.06f, 0.12f), wid = 0.45f * len;
    const vec3 corners[4] = {c - 0.5f * len * a - 0.5f * wid * b, c + 0.5f * len * a - 0.5f * wid * b,
                             c + 0.5f * len * a + 0.5f * wid * b, c - 0.5f * len * a + 0.5f * wid * b};
    for (int k = 0; k < 4; ++k) {
      leaves.positions.push_back(corners[k]);
      leaves.normals.push_back(n);
      leaves.uvs.push_back({float(k == 1 || k == 2), float(k >= 2)});
    }
    leaves.triangles.push_back({first_vertex, first_vertex + 1, first_vertex + 2});
    leaves.triangles.push_back({first_vertex, first_vertex + 2, first_vertex + 3});
    make_double_sided(leaves, first_vertex, first_triangle);
  }
};

}  // namespace

Scene make_tree_scene() {
  Scene s;
  s.name = "tree";
  TreeBuilder tree;
  tree.branch(vec3(0.0f), vec3(0, 1, 0), 2.2f, 0.22f, 5);
  add_object(s, tree.wood, "wood", add_material(s, diffuse("bark", {0.35f, 0.25f, 0.15f})));
  add_object(s, tree.leaves, "leaves", add_material(s, diffuse("leaf", {0.25f, 0.5f, 0.15f})));
  add_object(s, ground(20.0f), "ground", add_material(s, diffuse("grass", {0.3f, 0.4f, 0.2f})));
  finish(s, {0.0f, 3.5f, 11.0f}, {0.0f, 3.2f, 0.0f}, 45.0f, {5.0f, 15.0f, 8.0f}, 600.0f);
  return s;
}

}  // namespace proxima
