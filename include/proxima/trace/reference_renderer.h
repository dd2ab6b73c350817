// The reference renderer (ground truth, DESIGN.md "Reference = ground truth"): Embree ray
// casts for primary visibility, direct light with hard shadows (point lights) and n×n
// stratified light samples (area lights), second-order mirror and glossy reflections,
// environment lookup for escaping rays, optional k×k supersampling. The shading model is
// in docs/shading.md. Deterministic: per-pixel seeds from (seed, pixel), any thread count.
#pragma once

#include <cstdint>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// Primary visibility at pixel centers.
struct ItemBuffer {
  ImageU32 triangle;  // 1 channel; kNoTriangle where nothing was hit
  ImageF depth;       // 1 channel; −z_cam of the hit, +inf where nothing was hit
  ImageF normal;      // 3 channels; unit shading normal facing the camera, 0 on miss
  ImageF position;    // 3 channels; world position, 0 on miss
  ImageF barycentric; // 2 channels; Embree (u, v)
};

ItemBuffer trace_item_buffer(const Scene& scene, const RayScene& rays, const Camera& camera);

struct ReferenceOptions {
  int supersample = 1;          // k: k×k stratified sub-pixel samples (1 = pixel center)
  int area_light_samples = 4;   // n: n×n stratified samples per area light
  int glossy_rays = 16;         // rays in the glossy lobe per shading point (gloss > 0)
  int max_bounces = 2;          // reflection depth; 0 = no reflections
  uint64_t seed = 1;
};

// Linear RGB, 3 channels.
ImageF render_reference(const Scene& scene, const RayScene& rays, const Camera& camera,
                        const ReferenceOptions& options);

}  // namespace proxima
