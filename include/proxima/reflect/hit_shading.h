// The shading of a surface point seen along a reflection ray, shared by every reflection
// method and the Embree pass: shade_reflected_point for one point, HitShading for many at
// once (the same bits, the lights' sums in lanes), and the triangle reads both share.
#pragma once

#include <cstdint>
#include <vector>

#include "proxima/scene/scene.h"
#include "proxima/scene/shading.h"

namespace proxima {

// Radiance shading of a surface point seen from a reflection ray, shared by every method:
// docs/shading.md with reflected = 0 and direct light unshadowed (point lights and the n×n
// stratum centres of each area light). `toward_viewer` orients the two-sided surface.
vec3 shade_reflected_point(const Scene& scene, uint32_t triangle, float u, float v, vec3 toward_viewer,
                           int area_light_samples);

// What shading reads of a triangle, its vertices loaded once (a run of pixels or samples
// often shows one triangle): shading_normal and triangle_point from the loaded corners by
// the same expressions (the same bits), and the two-sided surface as seen from a viewer (as
// trace/'s surface_point_seen).
struct ShadedTriangle {
  // The geometric normal turned toward the viewer, the shading normal to its side.
  struct Facing {
    vec3 ng, n;
  };

  ShadedTriangle() = default;
  ShadedTriangle(const Scene& scene, uint32_t t)
      : triangle(t), ng(triangle_normal(scene, t)), material(&scene.materials[scene.triangle_material[t]]) {
    const uvec3& i = scene.triangles[t];
    n0 = scene.normals[i.x], n1 = scene.normals[i.y], n2 = scene.normals[i.z];
    p0 = scene.positions[i.x], p1 = scene.positions[i.y], p2 = scene.positions[i.z];
  }
  vec3 shading_normal(float u, float v) const {
    const vec3 n = barycentric(n0, n1, n2, u, v);
    const float len = glm::length(n);
    return len > 0.0f ? n / len : ng;
  }
  vec3 point(float u, float v) const { return barycentric(p0, p1, p2, u, v); }
  Facing facing(float u, float v, vec3 toward_viewer) const {
    Facing f;
    f.ng = ng;
    if (glm::dot(f.ng, toward_viewer) < 0.0f) f.ng = -f.ng;
    f.n = shading_normal(u, v);
    if (glm::dot(f.n, f.ng) < 0.0f) f.n = -f.n;
    return f;
  }

  uint32_t triangle = kNoTriangle;
  vec3 ng{0.0f};  // triangle_normal: the geometric normal, not yet facing the viewer
  const Material* material = nullptr;
  vec3 n0{0.0f}, n1{0.0f}, n2{0.0f}, p0{0.0f}, p1{0.0f}, p2{0.0f};
};

// shade_reflected_point's terms but the direct light: emission, ambient, albedo, s.
inline ShadingTerms terms_without_light(const Scene& scene, const Material& m, uint32_t t, float u, float v) {
  ShadingTerms st;
  st.emission = m.emission;
  st.ambient = scene.ambient;
  st.albedo = surface_diffuse(scene, t, u, v);
  st.specular = m.specular;
  return st;
}

// Whether the direct light adds to L at a point with these terms (a diffuse part to light).
inline bool receives_light(const ShadingTerms& st) { return st.specular < 1.0f && st.albedo != vec3(0.0f); }

// The lights as shade_reflected_point evaluates them, with what it recomputes per point
// (each area light's normal and area, its n×n stratum centres) computed once by the same
// expressions: the same values. Points are stored per coordinate for the lanes.
struct LightTable {
  struct Area {
    const AreaLight* light = nullptr;
    vec3 normal, radiance;
    float area = 0.0f;
    std::vector<float> x, y, z;  // the n×n stratum centres in shade_reflected_point's order
  };
  std::vector<PointLight> points;
  std::vector<Area> areas;
  float samples = 1.0f;  // float(n·n)

  LightTable(const Scene& scene, int area_light_samples);
};

// Lit points per coordinate (padded to whole lane groups) and their unshadowed direct
// irradiance.
struct LitPoints {
  std::vector<float> px, py, pz, nx, ny, nz, ex, ey, ez;
  size_t count = 0;

  void clear() { count = 0; }
  void add(vec3 p, vec3 n) {
    if (px.size() <= count) grow();
    px[count] = p.x, py[count] = p.y, pz[count] = p.z;
    nx[count] = n.x, ny[count] = n.y, nz[count] = n.z;
    ++count;
  }

 private:
  void grow();
};

// Hit points shaded as shade_reflected_point shades them, a block at a time: each point's
// terms as it arrives, the lit points' direct light together in lanes, so per point
// shade_reflected_point's bits (or the environment's colour, for a miss). Use: clear(), then
// add_hit / add_miss per point, finish(), then color[k] is the k-th point's radiance.
struct HitShading {
  explicit HitShading(const LightTable& table) : lights(&table) {}

  void clear();
  void add_miss(vec3 environment) { color.push_back(environment); }
  // The point (u, v) of triangle t seen along −toward_viewer.
  void add_hit(const Scene& scene, uint32_t t, float u, float v, vec3 toward_viewer) {
    if (t != run.triangle) run = ShadedTriangle(scene, t);
    const ShadingTerms st = terms_without_light(scene, *run.material, t, u, v);
    if (receives_light(st)) {
      lit.add(run.point(u, v), run.facing(u, v, toward_viewer).n);
      lit_index.push_back(uint32_t(color.size()));
      terms.push_back(st);
      color.emplace_back(0.0f);  // set by finish()
      return;
    }
    color.push_back(combine_shading(st));
  }
  // Completes `color` of the lit points.
  void finish();

  const LightTable* lights;
  std::vector<vec3> color;  // per point added, in order
  LitPoints lit;
  std::vector<ShadingTerms> terms;  // per lit point
  std::vector<uint32_t> lit_index;  // per lit point: its index in color
  ShadedTriangle run;               // the last triangle read
};

}  // namespace proxima
