// Algorithm 5 step 3 (thesis ch. 3, §3.3): per output pixel, which of the n×n light
// samples it sees — from one shadow map per light sample, or exactly with Embree rays.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/scene/scene.h"
#include "proxima/shadows/light_setup.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// One bit per (receiver pixel, light sample): 1 = the sample lights the pixel. A sample
// below a receiver's tangent plane (n · (s − p) ≤ 0) never does, nor does a one-sided light
// whose plane the receiver is behind (on_emitting_side false), for every method.
struct LightVisibility {
  int width = 0, height = 0, samples = 0;
  int words = 0;  // 64-bit words per pixel
  std::vector<uint64_t> bits;

  LightVisibility() = default;
  LightVisibility(int w, int h, int n_samples);
  bool lit(int x, int y, int s) const {
    return (bits[(size_t(y) * size_t(width) + size_t(x)) * size_t(words) + size_t(s >> 6)] >> (s & 63)) & 1u;
  }
  int lit_count(int x, int y) const;
};

// Shadow-map bias, in shadow-map texels at the receiver's depth: constant + slope·tan θ
// (θ between the receiver normal and the light direction, tan θ capped at kMaxBiasSlope).
// One texel of slack covers the nearest-texel lookup; the slope term the depth change
// across it on a slanted receiver.
//
// Texel density: that of a resolution² map over the light cameras' field of view, or, with
// footprint_texels > 0, the lower of that and footprint_texels texels per receiver
// footprint (the median distance between neighbouring receivers seen from the light's
// centre) along each axis — finer texels than the receivers' spacing buy little.
// fit_receivers: each map covers only what its receivers read — the light camera turned to
// the centre of their projection, the image cropped to it (plus a texel), the far plane at
// the farthest receiver (an occluder behind every receiver blocks none) — so a map has the
// texels and the triangles that can change an answer and no others. Without it every map
// covers the whole light-camera field (LightCameras) at `resolution`².
// per_map_tasks: each map is one task, drawn whole by one thread with the depth-only
// rasterizer (raster/depth_raster.h) and its receivers tested by the same thread, the maps
// in parallel; without it the maps go one after another, each through the tiled
// rasterizer (parallel over its tiles). The maps are bit-identical either way.
// read_texels_only (with per_map_tasks): a triangle whose pixel box holds none of the
// texels the receivers read is culled before its set-up (TexelMask, raster/depth_raster.h);
// the texels read get the same depth, so the answers are the same bits.
struct ShadowMapOptions {
  int resolution = 1024;
  float constant_bias = 1.5f;
  float slope_bias = 1.0f;
  bool fit_receivers = true;
  float footprint_texels = 0.0f;
  bool per_map_tasks = true;
  bool read_texels_only = true;
};
inline constexpr float kMaxBiasSlope = 10.0f;
// Largest side of a fitted map; a wider one gets coarser texels.
inline constexpr int kMaxFittedMapSide = 4096;

// What the shadow-map step did: wall time, texels and triangles drawn over all maps, and
// the self-check: receivers (facing their sample) outside a fitted map — a fitted map
// covers every receiver by construction, so any is a bug (a warning is printed).
struct ShadowMapStats {
  double ms = 0.0;
  double fit_ms = 0.0;     // fitting the maps' cameras
  double raster_ms = 0.0;  // rasterizing the maps (per_map_tasks: summed over the tasks)
  double test_ms = 0.0;    // the receivers' depth tests (likewise)
  uint64_t texels = 0;
  uint64_t triangles_drawn = 0;  // triangles the rasterizer set up (survived its culling)
  uint64_t receivers_outside = 0;
  float focal_px = 0.0f;  // the maps' focal length
};

// For each light sample: rasterize `occluders` (both sides, depth only) from the sample
// into a shadow map (options above), then test every receiver: lit iff its depth minus the
// bias is ≤ the map's nearest-texel depth (outside the map: lit). `ms` gets the wall time.
// Deterministic for any thread count.
LightVisibility shadow_map_visibility(const Scene& occluders, const Receivers& receivers,
                                      const LightSamples& samples, const LightCameras& cams,
                                      const ShadowMapOptions& options, double* ms = nullptr,
                                      ShadowMapStats* stats = nullptr);

// The shadow-map camera of light sample `eye` for `points` (the receivers' world
// positions) with focal length `focal_px` (fit_receivers above). Falls back to the whole
// light-camera field at the same focal length when a point is not in front of the light
// camera's near plane.
Camera fitted_shadow_map_camera(const LightCameras& cams, vec3 eye, std::span<const vec3> points, float focal_px);

// Exact visibility: an Embree shadow ray from each receiver (offset ε = 1e-4 × scene
// diagonal along its normal) to each light sample (stopping ε short).
LightVisibility ray_visibility(const RayScene& rays, const Scene& scene, const Receivers& receivers,
                               const LightSamples& samples, double* ms = nullptr);

}  // namespace proxima
