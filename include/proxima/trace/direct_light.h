// Local shading of a surface point (docs/shading.md): emission, ambient and Lambert direct
// light with Embree shadow rays — one per point light, n×n jittered stratified rays per
// area light — drawn from the caller's random stream. The reference renderer shades every
// hit with it, so an approximation of L_refl built on it (reflect/) differs from the
// reference only where it approximates the reflected radiance.
#pragma once

#include <cstdint>

#include "proxima/core/math.h"
#include "proxima/core/rng.h"
#include "proxima/scene/scene.h"
#include "proxima/scene/shading.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// A surface point seen along a direction, oriented like trace/: ng (unit geometric normal)
// faces back along the incoming direction, n (unit shading normal) lies in ng's hemisphere.
struct SurfacePoint {
  vec3 p;
  vec3 n;
  vec3 ng;
  uint32_t triangle;
  float u, v;  // Embree barycentrics
};

// `dir` points towards the surface (need not be unit).
SurfacePoint surface_point_seen(const Scene& scene, uint32_t triangle, float u, float v, vec3 dir);

class DirectLight {
 public:
  // `rays` must hold `scene`. area_light_samples = n of the n×n grid (as the reference's).
  DirectLight(const Scene& scene, const RayScene& rays, int area_light_samples);

  // Shading terms at sp with reflected = 0. Direct light is evaluated (and 2·n² numbers
  // per area light drawn from rng) only when (1 − s)·albedo ≠ 0, as the reference does.
  ShadingTerms local_terms(const SurfacePoint& sp, Pcg32& rng) const;

  // Secondary-ray origin: p moved off the surface along ng by 1e-4 × the scene diagonal.
  vec3 offset_origin(const SurfacePoint& sp) const { return sp.p + epsilon_ * sp.ng; }

 private:
  vec3 irradiance(const SurfacePoint& sp, Pcg32& rng) const;
  bool visible(vec3 origin, vec3 target) const;

  const Scene& scene_;
  const RayScene& rays_;
  int area_light_samples_;
  float epsilon_;
};

}  // namespace proxima
