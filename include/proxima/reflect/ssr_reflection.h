// Screen-space reflections, the engines' baseline beside the papers' methods: the reflection
// rays of a ReflectionFrame traced against the frame's own depth buffer — McGuire & Mara 2014
// (screen-space rays against a depth buffer with a thickness), with hierarchical-depth
// (min-max mip) traversal as AMD FidelityFX SSSR — and, where the depth buffer cannot answer
// (the ray leaves the screen or the view volume, passes behind a surface into the unknown,
// or runs out of steps), the box-projected probe (reflect/box_probe.h), then the environment.
//
// Screen space is the frame's sample camera (k·width × k·height, one pixel per G-buffer
// sample). Per pixel: the nearest surface's depth, triangle and barycentrics (the G-buffer),
// and the nearest back face's depth (a back-face pass) — the surface occupies [front, back]
// along the view ray, its thickness. Mip level l holds per 2^l × 2^l cell the minimum front
// and maximum back depth. A ray is a line in screen space along which x, y and 1/depth are
// affine; a cell is skipped (and the walk goes one level up) when the ray's depth over it is
// in front of every front or behind every back depth, else the walk goes one level down;
// at level 0 the pixel's surface plane (its triangle's, as a G-buffer normal gives it) decides
// whether the ray is still in front of it. A hit is shaded at the ray's crossing of that plane
// with the shared model (shade_reflected_point), so the error is the tracing alone.
//
// Confidence per ray, in [0, 1]: 0 where SSR found nothing (off screen, behind the near plane,
// step limit) and for a hit reached from behind a surface (the ray went into a surface's
// thickness from a region the depth buffer does not show: the classic hidden-surface guess);
// a hit within edge_fade of the border fades to 0 at the border. The ray's radiance is
// c·L_hit + (1 − c)·L_fallback.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/reflect/distance_cube_map.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/scene/scene.h"

namespace proxima {

struct SsrOptions {
  int max_steps = 256;          // traversal steps (cell visits) per ray at most, 1..65536
  float edge_fade = 0.05f;      // border band, × min(width, height) of the sample image, where confidence fades; [0, 0.5]
  float min_thickness = 0.01f;  // thickness × depth where the back-face pass gives nothing behind the surface; > 0
};

// The fallback of rays SSR cannot answer: the box-projected lookup on `map` with `box`
// (probe_proxy_box), or environment_radiance alone when map is null.
struct SsrFallback {
  const DistanceCubeMap* map = nullptr;
  Bounds3 box;
};

// Screen-space inputs of one camera: G-buffer and the min-max depth pyramid.
struct SsrDepth {
  Camera camera;
  ImageU32 triangle;                // level 0: nearest triangle, kNoTriangle where empty
  ImageF barycentric;               // 2 channels, its (u, v) at the pixel center
  std::vector<ImageF> front, back;  // per level: min front depth (+inf empty), max back depth (−inf empty)
  double gbuffer_ms = 0.0, backface_ms = 0.0, pyramid_ms = 0.0;
};

// Rasterizes `camera`'s depth, triangle and barycentric buffers (both sides, as the
// G-buffer), the back-face depth pass, and the pyramid. `object_bounds` as RasterOptions.
SsrDepth build_ssr_depth(const Scene& scene, const Camera& camera, float min_thickness,
                         std::span<const Bounds3> object_bounds = {});

enum class SsrOutcome : uint8_t {
  Hit,         // found a surface, entered from in front
  Hidden,      // found a surface's thickness entered from behind another (confidence 0)
  OffScreen,   // the ray left the image or crossed the near plane
  StepLimit,   // max_steps visits without a decision
  Exhausted,   // reached max_distance in front of everything
};

struct SsrHit {
  SsrOutcome outcome = SsrOutcome::OffScreen;
  float confidence = 0.0f;
  uint32_t triangle = 0xFFFFFFFFu;  // the surface found (Hit, Hidden)
  float u = 0.0f, v = 0.0f;         // its barycentrics at the shaded point
  int steps = 0;                    // cell visits
};

// Traces one ray (origin must be in front of the camera); max_distance bounds its length.
SsrHit trace_ssr_ray(const Scene& scene, const SsrDepth& depth, vec3 origin, vec3 dir, float max_distance,
                     const SsrOptions& options);

struct SsrStats {
  size_t samples = 0, rays = 0;
  size_t outcome_rays[5] = {};     // per SsrOutcome
  size_t fallback_rays = 0;        // rays with confidence < 1 (the fallback contributed)
  size_t fallback_samples = 0;     // reflective samples with at least one such ray
  size_t steps = 0;                // cell visits, all rays
  double confidence_sum = 0.0;     // over rays
  double gbuffer_ms = 0.0, backface_ms = 0.0, pyramid_ms = 0.0, trace_ms = 0.0;
  double total_ms() const { return gbuffer_ms + backface_ms + pyramid_ms + trace_ms; }
};

struct SsrReflections {
  std::vector<vec3> radiance;     // per reflective sample, mean over its rays
  std::vector<float> confidence;  // per reflective sample, mean over its rays
  SsrStats stats;
};

// SSR for every reflection ray of `frame` from its sample camera, with `fallback`.
// Deterministic for any thread count. Throws InputError for options out of range.
SsrReflections render_ssr_reflections(const Scene& scene, const ReflectionFrame& frame, const SsrOptions& options,
                                      const SsrFallback& fallback, std::span<const Bounds3> object_bounds = {});

// Throws InputError naming the option (ssr max_steps, edge_fade, min_thickness) out of range.
void validate(const SsrOptions& options);

}  // namespace proxima
