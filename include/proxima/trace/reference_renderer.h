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

// Primary visibility at pixel centers (rays clipped to the camera's [near, far] depth range).
struct ItemBuffer {
  ImageU32 triangle;   // 1 channel; kNoTriangle where nothing was hit
  ImageF depth;        // 1 channel; −z_cam of the hit, +inf where nothing was hit
  ImageF normal;       // 3 channels; unit shading normal facing the camera, 0 on miss
  ImageF position;     // 3 channels; world position, 0 on miss
  ImageF barycentric;  // 2 channels; Embree (u, v)
};

// `rays` must be built from `scene` (or updated to it). Throws InputError for an invalid camera.
ItemBuffer trace_item_buffer(const Scene& scene, const RayScene& rays, const Camera& camera);

// Sampling of render_reference (docs/shading.md); out-of-range values throw InputError.
struct ReferenceOptions {
  int supersample = 1;         // k in [1, 64]: k×k sub-pixel samples at the cell centers of
                               // a regular grid (1 = pixel center), averaged
  int area_light_samples = 4;  // n in [1, 256]: n×n jittered stratified samples per area light
  int glossy_rays = 16;        // [1, 4096] rays in the glossy lobe (gloss > 0) at the first
                               // bounce; deeper bounces follow the mirror direction only
  int max_bounces = 2;         // reflection depth in [0, 64]; 0 = no reflections
  uint64_t seed = 1;           // sub-sample streams: derive_seed(seed, pixel index, sub-sample)
  // Rows rendered, [row_begin, row_end) (−1 = to the last row); the others stay 0. Pixels
  // are the same bits as in a full render, so a viewer can build the image band by band.
  int row_begin = 0;
  int row_end = -1;
};

// The reference image: linear RGB, 3 channels, camera.width × camera.height.
// Throws InputError for an invalid camera (validate_camera) or options.
ImageF render_reference(const Scene& scene, const RayScene& rays, const Camera& camera,
                        const ReferenceOptions& options);

}  // namespace proxima
