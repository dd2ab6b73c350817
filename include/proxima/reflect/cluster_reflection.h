// Reflections from screen-space clustered depth images (thesis ch. 4, Algorithm 6), and the
// Embree pass that traces the identical reflection rays for comparison.
//
// A frame: (1) G-buffer from the eye at k×k samples per pixel and the reflection rays of
// every reflective sample (prepare_reflection_frame); (2) clusters of reflective samples;
// (3) per cluster a pinhole camera, a color + depth image rasterized from it, every ray of
// the cluster marched through that image (render_cluster_reflections); (4) the mean over
// each sample's rays blended in by s (compose_reflections). trace_reflections answers the
// same rays with Embree and the same shading, so the difference between the two images is
// the approximation alone. docs/cluster_reflections.md describes the choices.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/reflect/reflection_clustering.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// Sampling shared by the cluster method and its Embree reference.
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

// Step 1 of Algorithm 6 for one frame. Reflective samples are stored structure-of-arrays.
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
  double ms = 0.0;                  // G-buffer + ray set-up time

  size_t sample_count() const { return pixel.size(); }
};

// Rasterizes the G-buffer (depth, triangle, barycentrics, normal, object) from `camera` at
// k× resolution and builds every reflection ray exactly as render_reference does at its
// first bounce: mirror r = reflect(d, n), lobe directions glossy_lobe_direction() from the
// same stratified samples of the same per-sub-sample stream (unless lobe_seed_cell > 0). `object_bounds` as in
// RasterOptions (may be empty). Throws InputError for an invalid camera or options.
ReflectionFrame prepare_reflection_frame(const Scene& scene, const Camera& camera, const ReflectionOptions& options,
                                         std::span<const Bounds3> object_bounds = {});

// Radiance shading of a surface point seen from a reflection ray, shared by both methods:
// docs/shading.md with reflected = 0 and direct light unshadowed (point lights and the n×n
// stratum centres of each area light). `toward_viewer` orients the two-sided surface.
vec3 shade_reflected_point(const Scene& scene, uint32_t triangle, float u, float v, vec3 toward_viewer,
                           int area_light_samples);

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

struct ClusterReflectionOptions {
  ClusteringOptions clustering;
  float resolution_scale = 1.0f;    // cluster image texels per pixel footprint (Table 17)
  int max_image_side = 2048;        // cap per cluster image side
  float glossy_far_falloff = 0.5f;  // glossy far distance D = diagonal·(1 − falloff·g_max)
  float fade_fraction = 0.1f;       // glossy hits in the last fraction of D fade to the environment
  // Not in the thesis: clusters whose rays do not all pass through the camera centre (glossy
  // or curved) get a second layer, the nearest surface facing the camera at least
  // second_layer_separation (relative depth) behind the first, when one of their rays went
  // behind a nearer surface for good or found nothing; those rays are marched again in it
  // before falling back to fill_behind or the environment.
  bool second_layer = true;
  float second_layer_separation = 0.05f;
  int march_block = 0;  // > 0: block size of depth minima the march skips with (same result); 0 = none
};

// Why a ray's Embree hit is absent from its cluster image (the first cause that applies).
enum class OcclusionCause : uint8_t {
  None = 0,
  BehindNear = 1,    // behind the near (fitting) plane, clipped out of the image
  OutsideImage = 2,  // projects outside the cluster image (outside the frustum)
  OwnReflector = 3,  // on the cluster's own curved reflector, which its image leaves out
  Hidden = 4,        // inside the frustum, hidden behind nearer surfaces of the image (in every layer)
};
inline constexpr int kOcclusionCauses = 5;

// Statistics of one frame (counts exact, times wall-clock).
struct ClusterFrameStats {
  uint64_t clusters = 0;
  uint64_t reflective_samples = 0;
  uint64_t max_cluster_samples = 0;
  uint64_t texels = 0;                  // Σ cluster image pixels
  uint64_t objects_drawn = 0;           // Σ over cluster images, after frustum culling
  uint64_t env_fallback_samples = 0;    // samples with a ray that found no hit in its image
  uint64_t occlusion_error_samples = 0; // samples with a ray whose Embree hit is absent
                                        // from the cluster image (needs the reference)
  uint64_t behind_fill_samples = 0;     // samples with a ray answered by fill_behind
  uint64_t rays = 0;
  uint64_t occlusion_error_rays = 0;
  uint64_t mirror_samples = 0;                  // samples with g = 0 (one ray each)
  uint64_t mirror_occlusion_error_samples = 0;  // of those, occlusion errors
  uint64_t occlusion_cause_samples[kOcclusionCauses] = {};  // occlusion-error samples by the
                                                           // cause of their first such ray
  uint64_t second_layer_texels = 0;     // Σ second-layer image pixels
  uint64_t second_layer_rays = 0;       // rays answered by a hit in the second layer
  uint64_t planar_clusters = 0;
  uint64_t planar_samples = 0;          // samples in planar clusters
  double clustering_ms = 0.0;           // step 2
  double cameras_ms = 0.0;              // pixel footprints + cluster cameras (step 3a)
  double depth_images_ms = 0.0;         // rasterization + texel shading (step 3b), both layers
  double intersection_ms = 0.0;         // marching + blending over the lobe (step 3c)
};

// Per-sample flags of ClusterReflections::flags.
enum ClusterSampleFlag : uint8_t {
  kEnvFallback = 1u << 0,     // a ray found no hit in its cluster image (environment used)
  kOcclusionError = 1u << 1,  // a ray's Embree hit is absent from its cluster image
  kBehindFill = 1u << 2,      // a ray went behind a surface for good (MarchOptions::fill_behind)
  kSecondLayer = 1u << 3,     // a ray was answered by the second layer
};

struct ClusterReflections {
  std::vector<vec3> radiance;     // per sample: mean over its rays (G(d_i, g))
  std::vector<uint32_t> cluster;  // per sample: its cluster
  std::vector<uint8_t> flags;     // per sample: ClusterSampleFlag bits
  std::vector<uint8_t> occlusion_cause;  // per sample: OcclusionCause of its first occlusion-error ray
  ClusterFrameStats stats;
};

// Steps 2–3 of Algorithm 6 on a prepared frame. With `reference` (trace_reflections of the
// same frame) each ray's Embree hit is looked up in its cluster image to count occlusion
// errors. `object_bounds` as in RasterOptions. Deterministic for any thread count.
ClusterReflections render_cluster_reflections(const Scene& scene, const ReflectionFrame& frame,
                                              const ClusterReflectionOptions& options,
                                              std::span<const Bounds3> object_bounds = {},
                                              const TracedReflections* reference = nullptr);

// Final image (camera.width × camera.height, linear RGB): per sample base + s·reflected
// (reflected.size() == frame.sample_count()), box-filtered over the k×k samples.
ImageF compose_reflections(const ReflectionFrame& frame, std::span<const vec3> reflected);

// Output pixels with at least one reflective sample (1 channel, 0/1).
ImageU8 reflective_pixel_mask(const ReflectionFrame& frame);

}  // namespace proxima
