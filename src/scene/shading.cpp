// The shared shading model (docs/shading.md). Glossy lobe after the cluster-depth-image
// thesis, ch. 4 §4.6: reflection rays uniform in a cone around the mirror direction.
#include "proxima/scene/shading.h"

#include <algorithm>
#include <cmath>

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
  for (size_t r = 0; r < u.size(); ++r) out[r] = above_surface(cone.direction(u[r].x, u[r].y), n_facing);
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
  vec3 to_light = light_point - p;
  float r2 = glm::dot(to_light, to_light);
  if (r2 <= 0.0f) return vec3(0.0f);
  float r = std::sqrt(r2);
  float cos_surface = glm::dot(n, to_light) / r;
  float cos_light = -glm::dot(light.normal(), to_light) / r;
  if (cos_surface <= 0.0f || cos_light <= 0.0f) return vec3(0.0f);
  return light.radiance * (cos_surface * cos_light / r2 * light.area());
}

vec3 combine_shading(const ShadingTerms& t) {
  // Ambient stands for diffuse indirect light, so it is weighted like the diffuse part.
  return t.emission + (1.0f - t.specular) * t.albedo * (t.ambient + (1.0f / kPi) * t.direct_irradiance) +
         t.specular * t.reflected;
}

}  // namespace proxima
