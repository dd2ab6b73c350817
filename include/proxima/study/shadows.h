// The soft-shadow study (thesis ch. 3, Algorithms 4 and 5; docs/shadows.md): a rectangular
// area light, the scene sampled with depth images from the light and reconstructed into
// occluder meshes, the receivers' light visibility through shadow maps of those meshes,
// measured against shadow maps of the original geometry (the thesis' ground truth) and
// against exact Embree shadow rays.
#pragma once

#include <vector>

#include "proxima/core/progress.h"
#include "proxima/depthimage/sampling.h"
#include "proxima/eval/results.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"
#include "proxima/shadows/light_setup.h"
#include "proxima/shadows/light_visibility.h"
#include "proxima/shadows/occluders.h"
#include "proxima/study/study.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::study {

// The options of `proxima shadows`, one field per flag, with the flag's default.
struct ShadowsOptions {
  CameraChoice camera;  // --camera, --path, --frame: the output camera
  // --sampling; several share the ground truths (their metrics then carry a prefix).
  std::vector<ShadowSampling> samplings{ShadowSampling::Nrr};
  float light_size = 1.0f;  // --light-size: light diagonal / scene bounding-box diagonal, (0, 100]
  int light_samples = 16;   // --light-samples n: the light is sampled n × n, 1..64
  int ref_res = 1024;       // --ref-res, pixels (square), of the reference depth images
  int out_res = 512;        // --out-res, pixels (square), of the output image
  int shadow_res = 1024;    // --shadow-res: texel density of a shadow map this side (square) over the light field
  bool full_maps = false;   // --full-maps: every shadow map covers the whole light field (not fitted to the receivers)
  float shadow_footprint = 0.0f;  // --shadow-footprint: texels per receiver footprint, 0..16 (0: --shadow-res alone)
  Redundancy redundancy = Redundancy::Pixel;                          // --redundancy: NRR's test
  ReconstructionMethod reconstruction = ReconstructionMethod::Hybrid;  // --reconstruction
  bool no_rays = false;     // --no-rays: skip the Embree shadow-ray ground truth
};

// Throws InputError naming the flag (--sampling, --light-size, --light-samples, --ref-res,
// --out-res, --shadow-res, --shadow-footprint) for a value out of range; image sides are 8..kMaxImageSide.
void validate(const ShadowsOptions& options);
// The options on `scene`: validate(options), and the camera choice resolves (errors name
// --camera, --path or --frame).
void validate(const ShadowsOptions& options, const Scene& scene);

// What every sampling shares: the light and its n×n samples, the receivers (the visible
// points of `view`), the light cameras, the shadow maps of the original geometry (the
// thesis' ground truth: `truth`, `truth_ms`) and, unless no_rays, exact visibility by Embree
// shadow rays (`exact`, `rays_ms`). `rays` is the BVH of `scene`; `options` valid.
struct ShadowSetting {
  AreaLight light;
  LightSamples samples;
  Receivers receivers;
  LightCameras cams;
  ShadowMapOptions shadow_maps;
  LightVisibility truth, exact;
  ShadowMapStats truth_stats;
  double truth_ms = 0.0, rays_ms = 0.0;
};
ShadowSetting shadow_setting(const Scene& scene, const RayScene& rays, const Camera& view,
                             const ShadowsOptions& options);

// Steps 1–3 of one sampling on a setting: its occluders (ref_res, redundancy,
// reconstruction of `options`) and the receivers' visibility through their shadow maps
// (`shadow_ms`); Geometry: the setting's ground truth.
struct ShadowSamplingRun {
  Occluders occluders;
  LightVisibility visibility;
  ShadowMapStats stats;  // of the shadow maps (the setting's ground truth's for Geometry)
  double shadow_ms = 0.0;
};
ShadowSamplingRun run_shadow_sampling(const Scene& scene, const RayScene& rays, const ShadowSetting& setting,
                                      const ShadowsOptions& options, ShadowSampling sampling);

// Runs the study. Metrics per sampling (prefixed "<sampling>_" when several run):
// intensity_error_mean/_max, visibility_error_mean/_max (0..255, vs the geometry's shadow
// maps), with rays also intensity_error_rays_mean/_max, visibility_error_rays_mean/_max;
// time_reference_ms, time_reconstruct_ms, time_shadow_ms (of which time_shadow_raster_ms
// rasterizes the maps), shadow_texels and shadow_triangles_drawn (over all maps),
// occluder_triangles, reference_samples. Also light_size, light_samples (n²), receivers, triangles,
// light_fov_deg, time_geometry_shadow_ms, shadow_focal_px and, with rays, geometry_vs_rays_intensity_error_mean,
// geometry_vs_rays_visibility_error_mean, time_rays_ms. Tables: errors vs the geometry's
// shadow maps (thesis Table 8 shape), vs rays, time per step (Table 11 shape). Images:
// geometry_shadow, rays_shadow, <sampling>_shadow, <sampling>_error (green too bright, red
// too dark). Deterministic for any thread count but for the times; `progress` is not used
// (the study is one step of a caller's bar). Throws InputError for invalid options.
Results run_shadows(const Scene& scene, const ShadowsOptions& options, const StudyOutput& out,
                    Progress* progress = nullptr);

}  // namespace proxima::study
