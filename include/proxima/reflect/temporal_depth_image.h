// The reflection depth image of a key frame (thesis ch. 5 §5.3): per pixel of the key view
// B.1 normal s.n and depth s.d, B.2 reflectivity s.f, B.3 reflected radiance s.Lr and B.4
// the reflection distance s.r (reflector → reflected surface along the reflection ray).
// Built from a ReflectionFrame at one sample per pixel and the Embree trace of its rays, so
// the stored Lr is exactly what full reflection ray tracing gives at that frame.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/reflect/reflection_frame.h"

namespace proxima {

// Object id of pixels that show no reflector.
inline constexpr uint32_t kNoReflector = 0xFFFFFFFFu;

struct ReflectionDepthImage {
  Camera camera;      // key camera; E_old = camera.position
  ImageU32 object;    // reflector object id (p.rID), kNoReflector elsewhere
  ImageF position;    // W, world (3 channels), 0 elsewhere
  ImageF normal;      // s.n, unit shading normal facing E_old (3 channels)
  ImageF depth;       // s.d = −z_cam of W, +inf elsewhere
  ImageF specular;    // s.f: the material's s (proxima's blend weight, docs/temporal.md)
  ImageF radiance;    // s.Lr, mean over the sample's reflection rays (3 channels)
  ImageF distance;    // s.r, clamped to max_distance for rays that escape
  ImageF spread;      // how strongly the reflector bends the reflection here (mirror_spread)
  ImageF lobe;        // glossy lobe half-angle (radians), 0 on mirrors
  size_t reflective_pixels = 0;
  // Per key frame, for the steps every other frame runs: the reflective pixels (y·width + x,
  // row-major) and their reflected points R (key_reflected_point), in that order.
  std::vector<uint32_t> pixels;
  std::vector<vec3> reflected;
  // Set by every build from a process-wide counter: tells a rebuilt key frame (rebuilt in
  // place, so the same address) from the one a per-key-frame table was made for.
  uint64_t serial = 0;
};

// Mirror direction at a key pixel: reflect(W − E_old, s.n), unit.
vec3 key_mirror_direction(const ReflectionDepthImage& key, int x, int y);

// Reflected point R = W + reflect(W − E_old, s.n)·s.r (eq. 8).
vec3 key_reflected_point(const ReflectionDepthImage& key, int x, int y);

// Angle between the mirror directions of neighbouring key pixels over the angle between
// their view rays, the largest over the 4-neighbours on the same reflector; +inf when there
// is none. 1 on a planar mirror (reflection is an isometry of directions); about 1 + 2D/a
// on a convex mirror of radius a seen from distance D: it minifies the reflected scene by
// this factor, so a sub-pixel shift of the reflector changes what a pixel shows.
float mirror_spread(const ReflectionDepthImage& key, int x, int y);

// `frame` must be prepared at supersample 1 (std::logic_error otherwise); `traced` is
// trace_reflections of that frame. s.r is the mean finite hit distance over the sample's
// rays (its one mirror ray, or the glossy lobe), max_distance when all escape.
ReflectionDepthImage make_reflection_depth_image(const ReflectionFrame& frame, const TracedReflections& traced,
                                                 float max_distance);

// The same into `key`, reusing its images when they have the frame's size: only the pixels
// the earlier key frame wrote (its `pixels`) are reset, not nine whole images. Fresh large
// allocations cost more than the rest of the build on machines where page faults are slow
// (docs/temporal.md, "Speed of the per-frame steps"). The same result.
void make_reflection_depth_image_into(const ReflectionFrame& frame, const TracedReflections& traced,
                                      float max_distance, ReflectionDepthImage& key);

}  // namespace proxima
