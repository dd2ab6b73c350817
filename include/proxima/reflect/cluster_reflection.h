// Reflections from screen-space clustered depth images (thesis ch. 4, Algorithm 6) on a
// reflection frame (reflection_frame.h).
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
#include <optional>
#include <span>
#include <vector>

#include "proxima/core/image.h"
#include "proxima/reflect/cluster_camera.h"
#include "proxima/reflect/reflection_clustering.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/reflect/scene_lod.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

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
  // Not in the thesis: > 1, the lobe rays of glossy clusters march an image of the nearest
  // depth per glossy_march_coarse² block of texels (MarchOptions::coarse; colors still
  // from the full image); 1 = every ray marches the full image.
  int glossy_march_coarse = 1;
  // Each cluster image draws only the triangle blocks its frustum and clip plane can hold
  // (cluster_depth_image.h; identical images); false = every cluster draws the whole scene.
  bool cull = true;
  // Not in the thesis: a curved cluster's image leaves its own reflector out (its bulge in
  // front of the clip plane would hide what the rays hit), so a concave reflector's rays
  // that hit it elsewhere (a chair's back from its seat) are marched again, up to their
  // hit, in an own layer: that reflector alone, without the surface the rays start on
  // (fragments up to own_layer_separation footprints behind the cluster's points at their
  // texel). false = left out.
  bool own_layer = true;
  // With own_layer: true = instead of the own layer, each ray is intersected exactly with
  // its own reflector's triangles (ObjectBvh, built once per frame and reflector), up to its
  // hit so far: right per ray also where a strongly curved reflector's points overlap in the
  // camera's view. Makes the method a hybrid (one object ray-traced per curved cluster).
  bool own_exact = true;
  float own_layer_separation = 2.0f;
  int own_layer_scale = 4;       // own-layer texels per cluster-image texel, per axis
  int own_layer_max_side = 512;  // ... while its longer side stays at most this
  // Not in the thesis: with culling, lod_texels > 0 draws each object of a cluster image at
  // the coarsest level of detail (scene_lod.h) whose cell is at most lod_texels texel
  // footprints at the object's nearest depth; 0 = the exact triangles everywhere. `lod`:
  // the levels of the scene (build_scene_lod with lod_cells; built once per scene by the
  // caller); null = built in each call from the scene as posed.
  float lod_texels = 0.0f;
  const SceneLod* lod = nullptr;
};

// Levels of detail render_cluster_reflections builds when ClusterReflectionOptions::lod is
// null: lod_cells(scene diagonal, kClusterLodLevels).
inline constexpr int kClusterLodLevels = 9;

// Why a ray's Embree hit is absent from its cluster image (the first cause that applies).
enum class OcclusionCause : uint8_t {
  None = 0,
  BehindNear = 1,    // behind the near (fitting) plane, clipped out of the image
  OutsideImage = 2,  // projects outside the cluster image (outside the frustum)
  OwnReflector = 3,  // on the cluster's own curved reflector, absent from its own layer (own_exact: not
                     // the ray's own-reflector hit)
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
  uint64_t triangles_drawn = 0;         // Σ over cluster images (both layers), after culling
  uint64_t shaded_texels = 0;           // Σ first-layer texels shaded (those lookups read)
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
  uint64_t own_layer_texels = 0;        // Σ own-layer image pixels
  uint64_t own_layer_rays = 0;          // rays answered by a hit in the own layer (or own_exact test)
  uint64_t own_exact_triangles = 0;     // Σ triangles of the reflectors own_exact built a BVH over
  double own_exact_cpu_ms = 0.0;        // process CPU time of own_exact: BVH builds + ray tests
                                        // (inside depth_images / intersection CPU ms)
  uint64_t planar_clusters = 0;
  uint64_t planar_samples = 0;          // samples in planar clusters
  double clustering_ms = 0.0;           // step 2
  double cameras_ms = 0.0;              // pixel footprints + cluster cameras (step 3a)
  double depth_images_ms = 0.0;         // culling + rasterization + texel shading (step 3b), both layers
  double texel_shading_ms = 0.0;        // of depth_images_ms: the texel shading
  double intersection_ms = 0.0;         // marching + blending over the lobe (step 3c)
  // The same steps' process CPU time (all threads): steadier than wall-clock on a shared machine.
  double clustering_cpu_ms = 0.0, cameras_cpu_ms = 0.0, depth_images_cpu_ms = 0.0, intersection_cpu_ms = 0.0;
};

// Per-sample flags of ClusterReflections::flags.
enum ClusterSampleFlag : uint8_t {
  kEnvFallback = 1u << 0,     // a ray found no hit in its cluster image (environment used)
  kOcclusionError = 1u << 1,  // a ray's Embree hit is absent from its cluster image
  kBehindFill = 1u << 2,      // a ray went behind a surface for good (MarchOptions::fill_behind)
  kSecondLayer = 1u << 3,     // a ray was answered by the second layer
  kOwnLayer = 1u << 4,        // a ray was answered by the own layer (its own curved reflector)
};

struct ClusterReflections {
  std::vector<vec3> radiance;     // per sample: mean over its rays (G(d_i, g))
  std::vector<uint32_t> cluster;  // per sample: its cluster
  std::vector<uint8_t> flags;     // per sample: ClusterSampleFlag bits
  std::vector<uint8_t> occlusion_cause;  // per sample: OcclusionCause of its first occlusion-error ray
  std::vector<std::optional<ClusterCamera>> cameras;  // per cluster: its camera (none: environment only)
  ClusterFrameStats stats;
};

// Steps 2–3 of Algorithm 6 on a prepared frame. With `reference` (trace_reflections of the
// same frame) each ray's Embree hit is looked up in its cluster image to count occlusion
// errors. `object_bounds` as in RasterOptions. Deterministic for any thread count.
ClusterReflections render_cluster_reflections(const Scene& scene, const ReflectionFrame& frame,
                                              const ClusterReflectionOptions& options,
                                              std::span<const Bounds3> object_bounds = {},
                                              const TracedReflections* reference = nullptr);

}  // namespace proxima
