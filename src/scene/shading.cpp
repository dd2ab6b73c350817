// The shared shading model (docs/shading.md). Glossy lobe after the cluster-depth-image
// thesis, ch. 4 §4.6: reflection rays uniform in a cone around the mirror direction.
#include "proxima/scene/shading.h"

#include <algorithm>
#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace proxima {

vec3 reflect(vec3 dir, vec3 n) { return dir - 2.0f * glm::dot(dir, n) * n; }

float glossy_lobe_half_angle(float gloss) {
  return std::clamp(gloss, 0.0f, 1.0f) * glm::radians(kMaxGlossHalfAngleDeg);
}

namespace {

// The cone around a unit axis: 1 − cos α and the orthonormal basis (t1, t2) around the axis,
// without branches on its direction (Duff et al. 2017).
struct Cone {
  Cone(vec3 a, float half_angle) : axis(a), one_minus_cos(1.0f - std::cos(half_angle)) {
    const float sign = std::copysign(1.0f, axis.z);
    const float c = -1.0f / (sign + axis.z);
    const float b = axis.x * axis.y * c;
    t1 = {1.0f + sign * axis.x * axis.x * c, sign * b, -sign * axis.x};
    t2 = {b, sign + axis.y * axis.y * c, -axis.y};
  }
  // Uniform in solid angle: cos θ is uniform in [cos α, 1].
  vec3 direction(float u1, float u2) const {
    const float cos_theta = 1.0f - u1 * one_minus_cos;
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const float phi = 2.0f * kPi * u2;
    return glm::normalize(sin_theta * std::cos(phi) * t1 + sin_theta * std::sin(phi) * t2 + cos_theta * axis);
  }
#if defined(__SSE2__)
  // above_surface(direction(u[l].x, u[l].y), n) into out[l] for four samples: the angles and
  // libm's sine and cosine per sample, then the combination, normalization and fold four
  // lanes at once — per lane the scalar code's IEEE single operations in its order (glm's
  // dot (x·x' + y·y') + z·z', normalize v·(1/√(v·v)), the fold (2·below)·n; no fused
  // multiply-add on this target), so the same bits.
  void directions4(const vec2* u, vec3 n, vec3* out) const {
    alignas(16) float ct[4], st[4], c[4], s[4];
    for (int l = 0; l < 4; ++l) {
      ct[l] = 1.0f - u[l].x * one_minus_cos;
      st[l] = std::sqrt(std::max(0.0f, 1.0f - ct[l] * ct[l]));
      const float phi = 2.0f * kPi * u[l].y;
      c[l] = std::cos(phi);
      s[l] = std::sin(phi);
    }
    const __m128 cos_theta = _mm_load_ps(ct), sin_theta = _mm_load_ps(st);
    const __m128 a = _mm_mul_ps(sin_theta, _mm_load_ps(c)), b = _mm_mul_ps(sin_theta, _mm_load_ps(s));
    const auto coord = [&](float e1, float e2, float e) {
      return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a, _mm_set1_ps(e1)), _mm_mul_ps(b, _mm_set1_ps(e2))),
                        _mm_mul_ps(cos_theta, _mm_set1_ps(e)));
    };
    __m128 x = coord(t1.x, t2.x, axis.x), y = coord(t1.y, t2.y, axis.y), z = coord(t1.z, t2.z, axis.z);
    const auto dot = [](__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
      return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
    };
    const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(dot(x, y, z, x, y, z)));
    x = _mm_mul_ps(x, inv), y = _mm_mul_ps(y, inv), z = _mm_mul_ps(z, inv);
    const __m128 nx = _mm_set1_ps(n.x), ny = _mm_set1_ps(n.y), nz = _mm_set1_ps(n.z);
    const __m128 below = dot(x, y, z, nx, ny, nz);
    const __m128 above = _mm_cmpgt_ps(below, _mm_setzero_ps());  // NaN: false, folded as in the scalar code
    const __m128 twice = _mm_mul_ps(_mm_set1_ps(2.0f), below);
    const auto pick = [&](__m128 d, __m128 nd) {
      return _mm_or_ps(_mm_and_ps(above, d), _mm_andnot_ps(above, _mm_sub_ps(d, _mm_mul_ps(twice, nd))));
    };
    alignas(16) float ox[4], oy[4], oz[4];
    _mm_store_ps(ox, pick(x, nx));
    _mm_store_ps(oy, pick(y, ny));
    _mm_store_ps(oz, pick(z, nz));
    for (int l = 0; l < 4; ++l) out[l] = vec3(ox[l], oy[l], oz[l]);
  }
#endif
  vec3 axis;
  float one_minus_cos;
  vec3 t1, t2;
};

// Reflected back across the tangent plane when below it.
vec3 above_surface(vec3 d, vec3 n_facing) {
  const float below = glm::dot(d, n_facing);
  return below > 0.0f ? d : d - 2.0f * below * n_facing;
}

}  // namespace

vec3 sample_cone(vec3 axis, float half_angle, float u1, float u2) {
  if (half_angle <= 0.0f) return axis;
  return Cone(axis, half_angle).direction(u1, u2);
}

vec3 glossy_lobe_direction(vec3 mirror, vec3 n_facing, float half_angle, vec2 u) {
  return above_surface(sample_cone(mirror, half_angle, u.x, u.y), n_facing);
}

void glossy_lobe_directions(vec3 mirror, vec3 n_facing, float half_angle, std::span<const vec2> u,
                            std::span<vec3> out) {
  if (half_angle <= 0.0f) {
    for (size_t r = 0; r < u.size(); ++r) out[r] = above_surface(mirror, n_facing);
    return;
  }
  const Cone cone(mirror, half_angle);
  size_t r = 0;
#if defined(__SSE2__)
  for (; r + 4 <= u.size(); r += 4) cone.directions4(&u[r], n_facing, &out[r]);
#endif
  for (; r < u.size(); ++r) out[r] = above_surface(cone.direction(u[r].x, u[r].y), n_facing);
}

vec2 stratum_sample(int i, int j, int n, float xi1, float xi2) {
  float inv = 1.0f / float(n);
  // min keeps the point inside [0, 1) when (i + ξ)/n rounds up to 1.
  return {std::min((float(i) + xi1) * inv, 0x1.fffffep-1f), std::min((float(j) + xi2) * inv, 0x1.fffffep-1f)};
}

void stratified_samples_2d(std::span<vec2> out, Pcg32& rng) {
  int count = int(out.size());
  int m = int(std::lround(std::sqrt(double(count))));
  if (m * m == count) {
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        float xi1 = rng.next_float();
        float xi2 = rng.next_float();
        out[size_t(j * m + i)] = stratum_sample(i, j, m, xi1, xi2);
      }
    return;
  }
  // N-rooks: x strata in order, y strata shuffled (Fisher–Yates), each jittered.
  for (int k = 0; k < count; ++k) out[size_t(k)].y = float(k);
  for (int k = count - 1; k > 0; --k) std::swap(out[size_t(k)].y, out[rng.next_below(uint32_t(k + 1))].y);
  for (int k = 0; k < count; ++k) {
    float xi1 = rng.next_float();
    float xi2 = rng.next_float();
    out[size_t(k)] = stratum_sample(k, int(out[size_t(k)].y), count, xi1, xi2);
  }
}

vec3 point_light_irradiance(const PointLight& light, vec3 p, vec3 n) {
  vec3 to_light = light.position - p;
  float r2 = glm::dot(to_light, to_light);
  if (r2 <= 0.0f) return vec3(0.0f);
  float cos_theta = glm::dot(n, to_light) / std::sqrt(r2);
  return light.intensity * (std::max(0.0f, cos_theta) / r2);
}

vec3 area_light_sample_irradiance(const AreaLight& light, vec3 light_point, vec3 p, vec3 n) {
  return area_light_sample_irradiance(light, light.normal(), light.area(), light_point, p, n);
}

vec3 area_light_sample_irradiance(const AreaLight& light, vec3 light_normal, float light_area, vec3 light_point,
                                  vec3 p, vec3 n) {
  vec3 to_light = light_point - p;
  float r2 = glm::dot(to_light, to_light);
  if (r2 <= 0.0f) return vec3(0.0f);
  float r = std::sqrt(r2);
  float cos_surface = glm::dot(n, to_light) / r;
  float cos_light = -glm::dot(light_normal, to_light) / r;
  if (cos_surface <= 0.0f || cos_light <= 0.0f) return vec3(0.0f);
  return light.radiance * (cos_surface * cos_light / r2 * light_area);
}

vec3 combine_shading(const ShadingTerms& t) {
  // Ambient stands for diffuse indirect light, so it is weighted like the diffuse part.
  return t.emission + (1.0f - t.specular) * t.albedo * (t.ambient + (1.0f / kPi) * t.direct_irradiance) +
         t.specular * t.reflected;
}

}  // namespace proxima
