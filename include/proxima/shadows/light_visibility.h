// Algorithm 5 step 3 (thesis ch. 3, §3.3): per output pixel, which of the n×n light
// samples it sees — from one shadow map per light sample, or exactly with Embree rays.
#pragma once

#include <cstdint>
#include <vector>

#include "proxima/scene/scene.h"
#include "proxima/shadows/light_setup.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// One bit per (receiver pixel, light sample): 1 = the sample lights the pixel. A sample
// below a receiver's tangent plane (n · (s − p) ≤ 0) never does, for every method.
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
struct ShadowMapOptions {
  int resolution = 1024;
  float constant_bias = 1.5f;
  float slope_bias = 1.0f;
};
inline constexpr float kMaxBiasSlope = 10.0f;

// For each light sample: rasterize `occluders` (both sides, depth only) from the sample
// into a resolution² shadow map with `cams`, then test every receiver: lit iff its depth
// minus the bias is ≤ the map's nearest-texel depth (outside the map: lit). `ms` gets the
// wall time. Deterministic for any thread count.
LightVisibility shadow_map_visibility(const Scene& occluders, const Receivers& receivers,
                                      const std::vector<vec3>& samples, const LightCameras& cams,
                                      const ShadowMapOptions& options, double* ms = nullptr);

// Exact visibility: an Embree shadow ray from each receiver (offset ε = 1e-4 × scene
// diagonal along its normal) to each light sample (stopping ε short).
LightVisibility ray_visibility(const RayScene& rays, const Scene& scene, const Receivers& receivers,
                               const std::vector<vec3>& samples, double* ms = nullptr);

}  // namespace proxima
