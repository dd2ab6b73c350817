// The shading model every technique shares (docs/shading.md): Lambert diffuse under point
// and rectangular area lights, an unshadowed ambient term, emission, and a specular part
// that is the mean radiance over reflection rays in a uniform cone (the glossy lobe)
// around the mirror direction. Pure math: no ray casting here, so rasterizer-based
// techniques and the reference renderer (trace/) evaluate exactly the same formulas.
//
//   L = emission + (1 − s)·albedo·(ambient + Σ_lights E/π) + s·L_reflected
//
// Units: radiance in linear RGB; E is irradiance (intensity / r² for a point light);
// directions are world space; all angles in radians unless the name says _deg.
#pragma once

#include <span>

#include "proxima/core/math.h"
#include "proxima/core/rng.h"
#include "proxima/scene/light.h"

namespace proxima {

// Mirror reflection of the incident direction `dir` (pointing towards the surface) about
// the unit normal n: dir − 2·dot(dir, n)·n. Either side of n works; |result| = |dir|.
vec3 reflect(vec3 dir, vec3 n);

// Largest glossy lobe half-angle, reached at gloss g = 1.
inline constexpr float kMaxGlossHalfAngleDeg = 30.0f;

// Half-angle (radians) of the glossy lobe for gloss g in [0, 1]: g·30°. The lobe is a
// uniform cone around the mirror direction whose width grows with roughness, as in the
// cluster-depth-image thesis (ch. 4 §4.6), which samples reflection rays uniformly in such
// a lobe. g = 0 is a perfect mirror (half-angle 0). g is clamped to [0, 1].
float glossy_lobe_half_angle(float gloss);

// Unit direction uniformly distributed over the solid angle of the cone around the unit
// `axis` with `half_angle` in [0, π/2], from (u1, u2) in [0, 1)²: cosθ = 1 − u1·(1 − cos α),
// φ = 2π·u2. Stratified (u1, u2) give stratified directions (the map preserves area).
// half_angle = 0 returns axis.
vec3 sample_cone(vec3 axis, float half_angle, float u1, float u2);

// One lobe ray direction: sample_cone around `mirror`, then, if it points below the surface
// (dot with the unit normal `n_facing`, which faces the side the ray must leave from, ≤ 0),
// reflected back across the tangent plane so every lobe ray leaves the surface.
vec3 glossy_lobe_direction(vec3 mirror, vec3 n_facing, float half_angle, vec2 u);

// glossy_lobe_direction(mirror, n_facing, half_angle, u[r]) into out[r] for every r (out.size()
// = u.size()): the same bits, with what depends only on the cone (cos α, the basis around
// `mirror`) computed once.
void glossy_lobe_directions(vec3 mirror, vec3 n_facing, float half_angle, std::span<const vec2> u,
                            std::span<vec3> out);

// Fills `out` with out.size() stratified points in [0, 1)², drawing random numbers from
// `rng` in a fixed order: a jittered m×m grid (row-major cells) when out.size() = m², else
// N-rooks (Latin hypercube) with N = out.size(). Empty `out` draws nothing.
void stratified_samples_2d(std::span<vec2> out, Pcg32& rng);

// The jittered sample of stratum (i, j) of an n×n grid over [0, 1)²: ((i + ξ1)/n, (j + ξ2)/n).
vec2 stratum_sample(int i, int j, int n, float xi1, float xi2);

// Irradiance at point p with unit normal n from a point light, without shadowing:
// I·max(0, cos θ)/r² (θ between n and the direction to the light). 0 when r = 0.
vec3 point_light_irradiance(const PointLight& light, vec3 p, vec3 n);

// One-sample estimate of the irradiance at p (unit normal n) from an area light, sampled
// at `light_point` on it with pdf 1/area, without shadowing:
// L_e·max(0, cos θ)·max(0, cos θ_l)/r²·area, θ_l at the light (one-sided: only its front
// emits). Average n² stratified samples for the n×n estimate. 0 when r = 0.
vec3 area_light_sample_irradiance(const AreaLight& light, vec3 light_point, vec3 p, vec3 n);
// The same with the light's normal() and area() computed once by the caller for all its
// samples: the same value.
vec3 area_light_sample_irradiance(const AreaLight& light, vec3 light_normal, float light_area, vec3 light_point,
                                  vec3 p, vec3 n);

// What a shading point needs besides ray casting.
struct ShadingTerms {
  vec3 emission{0.0f};
  vec3 ambient{0.0f};            // Scene::ambient
  vec3 albedo{0.0f};             // surface_diffuse() at the point
  float specular = 0.0f;         // s in [0, 1]
  vec3 direct_irradiance{0.0f};  // Σ over lights of the (shadowed) irradiance E
  vec3 reflected{0.0f};          // mean radiance over the lobe (or mirror) rays
};

// L = emission + (1 − s)·albedo·(ambient + direct_irradiance/π) + s·reflected.
vec3 combine_shading(const ShadingTerms& terms);

}  // namespace proxima
