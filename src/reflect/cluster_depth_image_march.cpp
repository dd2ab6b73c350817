// Ray / depth-image intersection by marching the ray's projection one texel at a time.
// Paper: thesis ch. 4 §4.5, Algorithm 7. Symbols ↔ variables: R_begin, R_end ↔ begin, end;
// t_begin, t_end ↔ pb, pe (pixel coordinates instead of [0, 1]²); z_begin, z_end ↔ zb, ze;
// stepX, stepY ↔ the longer of |Δx|, |Δy| (steps); α ↔ alpha; depthR ↔ ray_depth(alpha)
// (1/depthR = (1 − α)/z_begin + α/z_end, the k1, k2 form); depthDI ↔ the texel depth.
// Algorithm 7 stops at the first step with depthR ≥ depthDI. Taken literally that also
// "hits" a nearer object the ray only passes behind; a hit here additionally needs the ray
// to have been in front of that surface one step earlier (within the surface's own depth
// change when the two texels are continuous), which tells silhouettes from surfaces; and
// since a step spans two texels, a ray that reaches the previous texel's surface within
// the step hits it even when the new texel holds a nearer occluder.
#include "proxima/reflect/depth_image_march.h"

#include <algorithm>
#include <cmath>

namespace proxima {

std::optional<DepthImageHit> march_depth_image(const Camera& camera, const ImageF& depth, vec3 begin, vec3 end,
                                               const MarchOptions& options) {
  auto b = project(camera, begin);
  auto e = project(camera, end);
  if (!b || !e) return std::nullopt;
  const vec2 pb = b->pixel, pe = e->pixel;
  const float inv_zb = 1.0f / b->depth, inv_ze = 1.0f / e->depth;
  const int w = depth.width(), h = depth.height();

  // Clip the screen segment pb + α·(pe − pb) to the image, α ∈ [a0, a1].
  float a0 = 0.0f, a1 = 1.0f;
  const vec2 d = pe - pb;
  const float lo[2] = {0.0f, 0.0f}, hi[2] = {float(w), float(h)};
  for (int axis = 0; axis < 2; ++axis) {
    if (std::abs(d[axis]) < 1e-12f) {
      if (pb[axis] < lo[axis] || pb[axis] >= hi[axis]) return std::nullopt;
      continue;
    }
    float t0 = (lo[axis] - pb[axis]) / d[axis], t1 = (hi[axis] - pb[axis]) / d[axis];
    if (t0 > t1) std::swap(t0, t1);
    a0 = std::max(a0, t0);
    a1 = std::min(a1, t1);
  }
  if (a0 > a1) return std::nullopt;

  auto ray_depth = [&](float alpha) { return 1.0f / ((1.0f - alpha) * inv_zb + alpha * inv_ze); };
  auto texel_depth = [&](float alpha) {
    vec2 s = pb + alpha * d;
    int x = std::clamp(int(std::floor(s.x)), 0, w - 1);
    int y = std::clamp(int(std::floor(s.y)), 0, h - 1);
    return depth.at(x, y);
  };

  // One step per texel along the longer screen axis; a segment inside one texel is one step.
  const float steps_f = std::max(std::abs(d.x), std::abs(d.y)) * (a1 - a0);
  const int steps = std::max(1, int(std::ceil(steps_f)));
  float prev_alpha = a0;
  float prev_ray = ray_depth(a0);
  float prev_surface = texel_depth(a0);
  std::optional<DepthImageHit> fill;
  for (int i = 1; i <= steps; ++i) {
    const float alpha = a0 + (a1 - a0) * float(i) / float(steps);
    const float ray = ray_depth(alpha);
    const float surface = texel_depth(alpha);
    if (ray >= surface) {
      const bool continuous = std::isfinite(prev_surface) &&
                              std::abs(surface - prev_surface) <= options.continuity * surface;
      const float slack = continuous ? std::abs(surface - prev_surface) : 0.0f;
      if (options.fill_behind && !fill && !continuous && prev_ray < prev_surface && std::isfinite(prev_surface))
        fill = DepthImageHit{pb + prev_alpha * d, prev_surface, true};
      if (prev_ray <= surface + slack) {
        // Where the ray reaches the stored depth (1/z is linear in α), kept inside the step.
        float hit_alpha = alpha;
        if (inv_ze != inv_zb) hit_alpha = std::clamp((1.0f / surface - inv_zb) / (inv_ze - inv_zb), prev_alpha, alpha);
        return DepthImageHit{pb + hit_alpha * d, surface};
      }
    }
    // A step spans two texels: the ray may reach the previous texel's surface before it
    // enters a nearer one (a silhouette just behind the hit).
    if (prev_ray <= prev_surface && ray >= prev_surface) {
      float hit_alpha = prev_alpha;
      if (inv_ze != inv_zb) hit_alpha = std::clamp((1.0f / prev_surface - inv_zb) / (inv_ze - inv_zb), prev_alpha, alpha);
      return DepthImageHit{pb + hit_alpha * d, prev_surface};
    }
    prev_alpha = alpha;
    prev_ray = ray;
    prev_surface = surface;
  }
  return fill;
}

}  // namespace proxima
