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

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace proxima {

namespace {

#if defined(__SSE2__)
// The constants of one march that the steps use.
struct MarchLine {
  float a0, span, steps;  // α of step i = a0 + span·i / steps
  vec2 pb, d;             // screen point at α = pb + α·d
  float inv_zb, inv_ze;   // 1/depthR = (1 − α)·inv_zb + α·inv_ze
  const float* depth;
  int w, h;
  float continuity;
};

// Steps i … i+3 computed four at a time with the scalar loop's operations in the same
// order (IEEE adds, multiplies and divides, no fused multiply-add: the same bits). True when
// none of them would do anything but move on — no hit, no fill, no crossing of the
// previous texel's surface — given the previous step's ray and surface depths; then
// `prev_*` become step i+3's values. False leaves everything to the scalar loop.
bool quiet_steps4(const MarchLine& m, int i, bool may_fill, float& prev_alpha, float& prev_ray,
                  float& prev_surface) {
  const __m128 fi = _mm_cvtepi32_ps(_mm_add_epi32(_mm_set1_epi32(i), _mm_set_epi32(3, 2, 1, 0)));
  const __m128 alpha = _mm_add_ps(_mm_set1_ps(m.a0), _mm_div_ps(_mm_mul_ps(_mm_set1_ps(m.span), fi), _mm_set1_ps(m.steps)));
  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 ray = _mm_div_ps(one, _mm_add_ps(_mm_mul_ps(_mm_sub_ps(one, alpha), _mm_set1_ps(m.inv_zb)),
                                                _mm_mul_ps(alpha, _mm_set1_ps(m.inv_ze))));
  // Texel = clamp(int(floor(pb + α·d)), 0, side − 1) per axis.
  auto texel = [&](float pb, float d, int side) {
    const __m128 s = _mm_add_ps(_mm_set1_ps(pb), _mm_mul_ps(alpha, _mm_set1_ps(d)));
    __m128i t = _mm_cvttps_epi32(s);
    t = _mm_add_epi32(t, _mm_castps_si128(_mm_cmpgt_ps(_mm_cvtepi32_ps(t), s)));  // truncation → floor
    t = _mm_and_si128(t, _mm_cmpgt_epi32(t, _mm_setzero_si128()));
    const __m128i top = _mm_set1_epi32(side - 1), over = _mm_cmpgt_epi32(t, top);
    return _mm_or_si128(_mm_and_si128(over, top), _mm_andnot_si128(over, t));
  };
  alignas(16) int tx[4], ty[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(tx), texel(m.pb.x, m.d.x, m.w));
  _mm_store_si128(reinterpret_cast<__m128i*>(ty), texel(m.pb.y, m.d.y, m.h));
  auto at = [&](int k) { return m.depth[size_t(ty[k]) * size_t(m.w) + size_t(tx[k])]; };
  const __m128 surface = _mm_set_ps(at(3), at(2), at(1), at(0));
  // The previous step's depths in lane k: step i−1's (the caller's) in lane 0, then the
  // lanes moved up by one (in registers: a store and overlapping reload would stall).
  auto previous = [](__m128 v, float before) {
    return _mm_move_ss(_mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 1, 0, 3)), _mm_set_ss(before));
  };
  const __m128 prev_s = previous(surface, prev_surface), prev_r = previous(ray, prev_ray);
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 prev_finite = _mm_cmplt_ps(_mm_and_ps(prev_s, abs_mask), _mm_set1_ps(kInf));
  const __m128 change = _mm_and_ps(_mm_sub_ps(surface, prev_s), abs_mask);
  const __m128 continuous = _mm_and_ps(prev_finite, _mm_cmple_ps(change, _mm_mul_ps(_mm_set1_ps(m.continuity), surface)));
  const __m128 slack = _mm_and_ps(continuous, change);
  const __m128 hits = _mm_cmple_ps(prev_r, _mm_add_ps(surface, slack));
  __m128 acts = hits;
  if (may_fill)
    acts = _mm_or_ps(acts, _mm_andnot_ps(continuous, _mm_and_ps(_mm_cmplt_ps(prev_r, prev_s), prev_finite)));
  const __m128 behind = _mm_and_ps(_mm_cmpge_ps(ray, surface), acts);
  const __m128 crosses = _mm_and_ps(_mm_cmple_ps(prev_r, prev_s), _mm_cmpge_ps(ray, prev_s));
  if (_mm_movemask_ps(_mm_or_ps(behind, crosses)) != 0) return false;
  auto last = [](__m128 v) { return _mm_cvtss_f32(_mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 3, 3, 3))); };
  prev_alpha = last(alpha);
  prev_ray = last(ray);
  prev_surface = last(surface);
  return true;
}
#endif

}  // namespace

namespace {
// The march over texel coordinates pb → pe (1/depth inv_zb → inv_ze) of `depth`.
std::optional<DepthImageHit> march_texels(vec2 pb, vec2 pe, float inv_zb, float inv_ze, const ImageF& depth,
                                          const MarchOptions& options);
}  // namespace

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
  return march_depth_image(CameraProjection(camera), depth, begin, end, options);
}

std::optional<DepthImageHit> march_depth_image(const CameraProjection& camera, const ImageF& depth, vec3 begin,
                                               vec3 end, const MarchOptions& options) {
  auto b = camera(begin);
  auto e = camera(end);
  if (!b || !e) return std::nullopt;
  const float to_texel = options.coarse > 1 ? 1.0f / float(options.coarse) : 1.0f;
  const vec2 pb = b->pixel * to_texel, pe = e->pixel * to_texel;
  if (options.coarse > 1) {
    auto hit = march_texels(pb, pe, 1.0f / b->depth, 1.0f / e->depth, depth, options);
    if (hit) hit->pixel *= float(options.coarse);
    return hit;
  }
  return march_texels(pb, pe, 1.0f / b->depth, 1.0f / e->depth, depth, options);
}

namespace {

std::optional<DepthImageHit> march_texels(vec2 pb, vec2 pe, float inv_zb, float inv_ze, const ImageF& depth,
                                          const MarchOptions& options) {
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
#if defined(__SSE2__)
  const MarchLine line{a0, a1 - a0, float(steps), pb, d, inv_zb, inv_ze, depth.data().data(), w, h, options.continuity};
#endif
  for (int i = 1; i <= steps; ++i) {
#if defined(__SSE2__)
    // Runs of steps that only move on are checked four at a time (not with block skipping,
    // which jumps on its own).
    if (!skip && options.batch) {
      while (i + 3 <= steps && quiet_steps4(line, i, options.fill_behind && !fill, prev_alpha, prev_ray, prev_surface))
        i += 4;
      if (i > steps) break;
    }
#endif
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

}  // namespace

}  // namespace proxima
