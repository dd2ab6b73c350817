// Local shading with Embree shadows: the reference renderer's (trace/reference_renderer.cpp)
// and the one techniques in reflect/ shade environment texels and reflector pixels with.
#include "proxima/trace/direct_light.h"

#include <algorithm>

namespace proxima {

namespace {
// Same relative offset as the reference renderer (docs/shading.md "Ray offsets").
constexpr float kRelativeEpsilon = 1e-4f;
}  // namespace

SurfacePoint surface_point_seen(const Scene& scene, uint32_t triangle, float u, float v, vec3 dir) {
  SurfacePoint sp;
  sp.triangle = triangle;
  sp.u = u;
  sp.v = v;
  sp.p = triangle_point(scene, triangle, u, v);
  sp.ng = triangle_normal(scene, triangle);
  if (glm::dot(sp.ng, dir) > 0.0f) sp.ng = -sp.ng;
  sp.n = shading_normal(scene, triangle, u, v);
  if (glm::dot(sp.n, sp.ng) < 0.0f) sp.n = -sp.n;
  return sp;
}

DirectLight::DirectLight(const Scene& scene, const RayScene& rays, int area_light_samples)
    : scene_(scene),
      rays_(rays),
      area_light_samples_(area_light_samples),
      epsilon_(kRelativeEpsilon * std::max(scene_bounds(scene).diagonal(), 1e-3f)) {}

ShadingTerms DirectLight::local_terms(const SurfacePoint& sp, Pcg32& rng) const {
  const Material& m = scene_.materials[scene_.triangle_material[sp.triangle]];
  ShadingTerms terms;
  terms.emission = m.emission;
  terms.ambient = scene_.ambient;
  terms.albedo = surface_diffuse(scene_, sp.triangle, sp.u, sp.v);
  terms.specular = m.specular;
  if (m.specular < 1.0f && terms.albedo != vec3(0.0f)) terms.direct_irradiance = irradiance(sp, rng);
  return terms;
}

bool DirectLight::visible(vec3 origin, vec3 target) const {
  vec3 d = target - origin;
  float length = glm::length(d);
  if (length <= epsilon_) return true;
  return !rays_.occluded(Ray{origin, d, 0.0f, 1.0f - epsilon_ / length});
}

vec3 DirectLight::irradiance(const SurfacePoint& sp, Pcg32& rng) const {
  vec3 origin = offset_origin(sp);
  vec3 sum(0.0f);
  for (const PointLight& light : scene_.point_lights) {
    vec3 e = point_light_irradiance(light, sp.p, sp.n);
    if (e != vec3(0.0f) && visible(origin, light.position)) sum += e;
  }
  const int n = area_light_samples_;
  for (const AreaLight& light : scene_.area_lights) {
    const vec3 normal = light.normal();
    const float area = light.area();
    vec3 light_sum(0.0f);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        float xi1 = rng.next_float();
        float xi2 = rng.next_float();
        vec2 ab = stratum_sample(i, j, n, xi1, xi2);
        vec3 q = light.point(ab.x, ab.y);
        vec3 e = area_light_sample_irradiance(light, normal, area, q, sp.p, sp.n);
        if (e != vec3(0.0f) && visible(origin, q)) light_sum += e;
      }
    sum += light_sum / float(n * n);
  }
  return sum;
}

}  // namespace proxima
