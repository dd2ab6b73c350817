// shade_reflected_point and its many-point form HitShading: the same model, the same bits.
#include "proxima/reflect/hit_shading.h"

#include <algorithm>
#include <cmath>

#include "shading_lanes.h"

namespace proxima {

vec3 shade_reflected_point(const Scene& scene, uint32_t triangle, float u, float v, vec3 toward_viewer,
                           int area_light_samples) {
  const ShadedTriangle tri(scene, triangle);
  const Material& m = *tri.material;
  const ShadedTriangle::Facing f = tri.facing(u, v, toward_viewer);
  const vec3 p = tri.point(u, v);
  ShadingTerms terms = terms_without_light(scene, m, triangle, u, v);
  if (receives_light(terms)) {
    for (const PointLight& light : scene.point_lights) terms.direct_irradiance += point_light_irradiance(light, p, f.n);
    const int n = area_light_samples;
    for (const AreaLight& light : scene.area_lights) {
      const vec3 normal = light.normal();
      const float area = light.area();
      vec3 sum(0.0f);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          vec2 ab = stratum_sample(i, j, n, 0.5f, 0.5f);
          sum += area_light_sample_irradiance(light, normal, area, light.point(ab.x, ab.y), p, f.n);
        }
      terms.direct_irradiance += sum / float(n * n);
    }
  }
  return combine_shading(terms);
}

LightTable::LightTable(const Scene& scene, int n) : points(scene.point_lights), samples(float(n * n)) {
  for (const AreaLight& light : scene.area_lights) {
    Area a;
    a.light = &light;
    a.normal = light.normal();
    a.radiance = light.radiance;
    a.area = light.area();
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const vec2 ab = stratum_sample(i, j, n, 0.5f, 0.5f);
        const vec3 q = light.point(ab.x, ab.y);
        a.x.push_back(q.x);
        a.y.push_back(q.y);
        a.z.push_back(q.z);
      }
    areas.push_back(std::move(a));
  }
}

void LitPoints::grow() {
  // Sizes stay multiples of the widest lane group: the lanes read whole groups.
  for (auto* v : {&px, &py, &pz, &nx, &ny, &nz, &ex, &ey, &ez}) v->resize(std::max<size_t>(64, 2 * count), 0.0f);
}

namespace {

#if PROXIMA_SHADE_LANES
// The direct irradiance of shade_reflected_point for L::kWidth points at once: each lane
// runs point_light_irradiance's and area_light_sample_irradiance's IEEE single operations
// in their order (dot = (x·x' + y·y') + z·z', max(0, c) as 0 < c ? c : +0, a returned 0
// added as +0; no fused multiply-add on these targets, so nothing is contracted): per lane
// the scalar code's bits.
template <class L>
inline __attribute__((always_inline)) void direct_irradiance_lanes(const LightTable& lights, LitPoints& lit) {
  using V = typename L::V;
  for (size_t i = 0; i < lit.count; i += L::kWidth) {
    const V px = L::load(&lit.px[i]), py = L::load(&lit.py[i]), pz = L::load(&lit.pz[i]);
    const V nx = L::load(&lit.nx[i]), ny = L::load(&lit.ny[i]), nz = L::load(&lit.nz[i]);
    V ex = L::zero(), ey = L::zero(), ez = L::zero();
    for (const PointLight& light : lights.points) {
      const V tx = L::sub(L::set1(light.position.x), px);
      const V ty = L::sub(L::set1(light.position.y), py);
      const V tz = L::sub(L::set1(light.position.z), pz);
      const V r2 = L::dot(tx, ty, tz, tx, ty, tz);
      const V c = L::div(L::dot(nx, ny, nz, tx, ty, tz), L::sqrt(r2));
      const V q = L::div(L::keep(L::gt0(c), c), r2);  // max(0, c) / r²
      const V keep = L::not_le0(r2);                   // r² <= 0 gives 0
      ex = L::add(ex, L::keep(keep, L::mul(L::set1(light.intensity.x), q)));
      ey = L::add(ey, L::keep(keep, L::mul(L::set1(light.intensity.y), q)));
      ez = L::add(ez, L::keep(keep, L::mul(L::set1(light.intensity.z), q)));
    }
    for (const LightTable::Area& a : lights.areas) {
      const V lnx = L::set1(a.normal.x), lny = L::set1(a.normal.y), lnz = L::set1(a.normal.z);
      const V area = L::set1(a.area);
      const V rx = L::set1(a.radiance.x), ry = L::set1(a.radiance.y), rz = L::set1(a.radiance.z);
      V sx = L::zero(), sy = L::zero(), sz = L::zero();
      for (size_t k = 0; k < a.x.size(); ++k) {
        const V tx = L::sub(L::set1(a.x[k]), px);
        const V ty = L::sub(L::set1(a.y[k]), py);
        const V tz = L::sub(L::set1(a.z[k]), pz);
        const V r2 = L::dot(tx, ty, tz, tx, ty, tz);
        const V r = L::sqrt(r2);
        const V cs = L::div(L::dot(nx, ny, nz, tx, ty, tz), r);
        const V cl = L::div(L::neg(L::dot(lnx, lny, lnz, tx, ty, tz)), r);
        const V f = L::mul(L::div(L::mul(cs, cl), r2), area);
        // 0 where r² <= 0, cos_surface <= 0 or cos_light <= 0 (NaN passes, as in the scalar test)
        const V keep = L::both(L::not_le0(r2), L::both(L::not_le0(cs), L::not_le0(cl)));
        sx = L::add(sx, L::keep(keep, L::mul(rx, f)));
        sy = L::add(sy, L::keep(keep, L::mul(ry, f)));
        sz = L::add(sz, L::keep(keep, L::mul(rz, f)));
      }
      const V m = L::set1(lights.samples);
      ex = L::add(ex, L::div(sx, m));
      ey = L::add(ey, L::div(sy, m));
      ez = L::add(ez, L::div(sz, m));
    }
    L::store(&lit.ex[i], ex);
    L::store(&lit.ey[i], ey);
    L::store(&lit.ez[i], ez);
  }
}

#if PROXIMA_SHADE_AVX
__attribute__((target("avx"), flatten)) void direct_irradiance_avx(const LightTable& lights, LitPoints& lit) {
  direct_irradiance_lanes<Lanes8>(lights, lit);
}
#endif

void direct_irradiance(const LightTable& lights, LitPoints& lit) {
#if PROXIMA_SHADE_AVX
  if (has_avx()) return direct_irradiance_avx(lights, lit);
#endif
  direct_irradiance_lanes<Lanes4>(lights, lit);
}
#else
void direct_irradiance(const LightTable& lights, LitPoints& lit) {
  for (size_t i = 0; i < lit.count; ++i) {
    const vec3 p(lit.px[i], lit.py[i], lit.pz[i]), n(lit.nx[i], lit.ny[i], lit.nz[i]);
    vec3 e(0.0f);
    for (const PointLight& light : lights.points) e += point_light_irradiance(light, p, n);
    for (const LightTable::Area& a : lights.areas) {
      vec3 sum(0.0f);
      for (size_t k = 0; k < a.x.size(); ++k)
        sum += area_light_sample_irradiance(*a.light, a.normal, a.area, vec3(a.x[k], a.y[k], a.z[k]), p, n);
      e += sum / lights.samples;
    }
    lit.ex[i] = e.x, lit.ey[i] = e.y, lit.ez[i] = e.z;
  }
}
#endif

}  // namespace

void HitShading::clear() {
  lit.clear();
  color.clear();
  terms.clear();
  lit_index.clear();
}

void HitShading::finish() {
  direct_irradiance(*lights, lit);
  for (size_t k = 0; k < lit_index.size(); ++k) {
    terms[k].direct_irradiance = vec3(lit.ex[k], lit.ey[k], lit.ez[k]);
    color[lit_index[k]] = combine_shading(terms[k]);
  }
}

}  // namespace proxima
