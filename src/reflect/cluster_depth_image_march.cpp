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

ImageF depth_block_min(const ImageF& depth, int block) {
  const int w = depth.width(), h = depth.height();
  const int bw = (w + block - 1) / block, bh = (h + block - 1) / block;
  ImageF out(bw, bh, 1, kInf);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float& m = out.at(x / block, y / block);
      m = std::min(m, depth.at(x, y));
    }
  return out;
}

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
  auto texel_of = [&](float alpha) {
    vec2 s = pb + alpha * d;
    return ivec2(std::clamp(int(std::floor(s.x)), 0, w - 1), std::clamp(int(std::floor(s.y)), 0, h - 1));
  };
  auto texel_depth = [&](float alpha) {
    const ivec2 t = texel_of(alpha);
    return depth.at(t.x, t.y);
  };

  // One step per texel along the longer screen axis; a segment inside one texel is one step.
  const float steps_f = std::max(std::abs(d.x), std::abs(d.y)) * (a1 - a0);
  const int steps = std::max(1, int(std::ceil(steps_f)));
  auto alpha_of = [&](int i) { return a0 + (a1 - a0) * float(i) / float(steps); };
  const int B = options.block;
  const bool skip = options.block_min != nullptr && B > 0;
  // Last step index ≥ i whose texel lies in the same block as step i's (the steps in a
  // block are consecutive: a block is convex and the clamp is monotone).
  auto last_step_in_block = [&](int i) {
    const ivec2 blk = texel_of(alpha_of(i)) / B;
    auto inside = [&](int j) { return texel_of(alpha_of(j)) / B == blk; };
    // Estimate from where the screen segment leaves the block, then correct by stepping.
    float exit_alpha = a1;
    for (int axis = 0; axis < 2; ++axis) {
      if (d[axis] > 0.0f && blk[axis] < (axis ? h - 1 : w - 1) / B)
        exit_alpha = std::min(exit_alpha, (float((blk[axis] + 1) * B) - pb[axis]) / d[axis]);
      if (d[axis] < 0.0f && blk[axis] > 0) exit_alpha = std::min(exit_alpha, (float(blk[axis] * B) - pb[axis]) / d[axis]);
    }
    int j = std::clamp(int((exit_alpha - a0) / (a1 - a0) * float(steps)), i, steps);
    while (j > i && !inside(j)) --j;
    while (j < steps && inside(j + 1)) ++j;
    return j;
  };
  float prev_alpha = a0;
  float prev_ray = ray_depth(a0);
  float prev_surface = texel_depth(a0);
  std::optional<DepthImageHit> fill;
  for (int i = 1; i <= steps; ++i) {
    const float alpha = alpha_of(i);
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
    if (skip && i < steps) {
      // Steps i+1 … j in step i's block, where the ray stays in front of the block's nearest
      // texel, can neither hit nor pass behind anything (1/z is linear in α, so the ray depth
      // is monotone and its values at steps i and j bound it). Jump to j. The cheap test
      // on step i comes first; j is only looked for when it passes.
      const ivec2 blk = texel_of(alpha) / B;
      const float nearest = options.block_min->at(blk.x, blk.y);
      if (ray < nearest) {
        const int j = last_step_in_block(i);
        if (j > i && ray_depth(alpha_of(j)) < nearest) {
          i = j;
          prev_alpha = alpha_of(j);
          prev_ray = ray_depth(prev_alpha);
          prev_surface = texel_depth(prev_alpha);
        }
      }
    }
  }
  return fill;
}

}  // namespace proxima
