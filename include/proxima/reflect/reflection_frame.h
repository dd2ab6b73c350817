// The reflection frame every reflection method starts from, and its Embree reference: the
// G-buffer from the eye at k×k samples per pixel, every reflective sample's reflection rays
// (mirror or glossy lobe, drawn exactly as render_reference's first bounce), Embree's answer
// for the same rays shaded as hit_shading.h shades a reflected point, and the final blend
// base + s·reflected.
// The cluster method (cluster_reflection.h), the env-map lookups (envmap_frame_reflections.h)
// and temporal reuse (temporal_reuse.h) each replace trace_reflections' radiance; the
// difference between their image and the traced one is the approximation alone.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// Ray origins are pushed off the surface by this × the scene diagonal along the geometric
// normal: the reference renderer's offset (docs/shading.md).
inline constexpr float kReflectionRayOffset = 1e-4f;


// Sampling shared by every reflection method and its Embree reference.
struct ReflectionOptions {
  int supersample = 2;         // k in [1, 8]: samples at the reference renderer's k×k sub-pixel positions
  int glossy_rays = 8;         // [1, 1024] lobe rays per sample on glossy surfaces (g > 0); mirrors cast one
  int area_light_samples = 4;  // n in [1, 64] of render_reference: its random stream is skipped
                               // the same way so lobe samples match; reflected and eye-visible
                               // points see area lights through the n×n stratum centres
  uint64_t seed = 1;
  // > 0: glossy lobe samples are seeded by the surface point instead of the pixel — by the
  // world-space cell of this edge length (× the scene diagonal) that holds it — so a point
  // draws the same lobe rays in every frame and from every view (temporally stable glossy
  // reflections; temporal reuse then carries no other pixel's noise). Pixels in one cell
  // share their lobe directions. 0: per-pixel streams, as render_reference.
  float lobe_seed_cell = 0.0f;
};

// One frame (step 1 of the thesis' Algorithm 6). Reflective samples are stored structure-of-arrays.
struct ReflectionFrame {
  Camera camera;         // the output camera (width × height)
  Camera sample_camera;  // the same at k·width × k·height: one G-buffer pixel per sample
  int supersample = 1;
  int area_light_samples = 4;  // n of ReflectionOptions, for shade_reflected_point
  // Per G-buffer pixel: L without the reflected term (emission + (1 − s)·diffuse part), or
  // the environment where nothing is seen. 3 channels.
  ImageF base;
  // Reflective samples (s > 0):
  std::vector<uint32_t> pixel;      // G-buffer pixel index y·(k·width) + x
  std::vector<vec3> position;       // P_i, world
  std::vector<vec3> normal;         // n_i, unit shading normal facing the eye
  std::vector<vec3> origin;         // ray origin: P_i pushed off the surface along n_g
  std::vector<uint32_t> reflector;  // object id, p.rID
  std::vector<float> specular;      // s
  std::vector<float> gloss;         // g
  std::vector<uint32_t> first_ray;  // sample i owns directions [first_ray[i], first_ray[i+1])
  std::vector<vec3> direction;      // unit reflection ray directions (lobe samples)
  float scene_diagonal = 0.0f;
  double ms = 0.0;                  // G-buffer + ray set-up time (wall clock), and its phases:
  double raster_ms = 0.0;           // rasterizing the G-buffer
  double shading_ms = 0.0;          // the base shading
  double rays_ms = 0.0;             // listing the reflective samples and building their rays

  size_t sample_count() const { return pixel.size(); }
};

// Rasterizes the G-buffer (triangle and barycentrics per sample) from `camera` at
// k× resolution and builds every reflection ray exactly as render_reference does at its
// first bounce: mirror r = reflect(d, n), lobe directions glossy_lobe_direction() from the
// same stratified samples of the same per-sub-sample stream (unless lobe_seed_cell > 0). `object_bounds` as in
// RasterOptions (may be empty). Throws InputError for an invalid camera or options.
ReflectionFrame prepare_reflection_frame(const Scene& scene, const Camera& camera, const ReflectionOptions& options,
                                         std::span<const Bounds3> object_bounds = {});
// The same into `frame`, reusing its buffers (a walk renders into one frame: no fresh pages
// per frame). Every field is rewritten; the result equals prepare_reflection_frame's.
void prepare_reflection_frame_into(const Scene& scene, const Camera& camera, const ReflectionOptions& options,
                                   ReflectionFrame& frame, std::span<const Bounds3> object_bounds = {});

// The reflections traced by Embree: per sample the mean radiance over its rays, per ray the
// closest hit (triangle kNoTriangle and t = +inf when the ray escapes; the hit point is
// origin + t·direction).
struct TracedReflections {
  std::vector<vec3> radiance;
  std::vector<uint32_t> hit_triangle;
  std::vector<float> hit_t;
  double ms = 0.0;
};

// `rays` must be built from the scene the frame was prepared on.
TracedReflections trace_reflections(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame);

// The same into `out`, reusing its vectors' memory (no fresh pages per frame): the same result.
void trace_reflections_into(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                            TracedReflections& out);

// trace_reflections' radiance of the listed samples alone (the same rays, shading and order
// of accumulation: the same bits), written to radiance[i] of each listed i; no hits kept.
void trace_reflection_samples(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                              std::span<const uint32_t> samples, std::span<vec3> radiance);

// Final image (camera.width × camera.height, linear RGB): per sample base + s·reflected
// (reflected.size() == frame.sample_count()), box-filtered over the k×k samples.
ImageF compose_reflections(const ReflectionFrame& frame, std::span<const vec3> reflected);
// The same into `out`, reusing its memory when it has the output's size.
void compose_reflections_into(const ReflectionFrame& frame, std::span<const vec3> reflected, ImageF& out);

// Output pixels with at least one reflective sample (1 channel, 0/1).
ImageU8 reflective_pixel_mask(const ReflectionFrame& frame);

}  // namespace proxima
