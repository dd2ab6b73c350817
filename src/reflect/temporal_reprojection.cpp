// Depth-based reprojection (thesis ch. 5 §5.4, step 3), as a gather over the new frame's
// reflective samples: deterministic, and each sample gets exactly one answer or a flag.
#include "proxima/reflect/temporal_reprojection.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include "proxima/core/parallel.h"

namespace proxima {

namespace {
constexpr size_t kSampleGrain = 1024;
}  // namespace

ReflectionReprojection reproject_reflections(const ReflectionFrame& frame, const ReflectionDepthImage& key,
                                             const ImageF& radiance, const ImageU8* state,
                                             const ReprojectOptions& options, const WarpedMesh* mesh) {
  ReflectionReprojection out;
  reproject_reflections_into(frame, key, radiance, state, options, mesh, out);
  return out;
}

void reproject_reflections_into(const ReflectionFrame& frame, const ReflectionDepthImage& key, const ImageF& radiance,
                                const ImageU8* state, const ReprojectOptions& options, const WarpedMesh* mesh,
                                ReflectionReprojection& out) {
  if (frame.supersample != 1) throw std::logic_error("reprojection: frame must have supersample 1");
  const size_t n = frame.sample_count();
  const int kw = key.object.width(), kh = key.object.height();
  out.radiance.assign(n, vec3(0.0f));  // in the vectors' memory when they have room: no fresh pages
  out.flag.assign(n, kReuseOk);
  out.disoccluded = out.unreliable = out.curved = out.edge = 0;
  auto same_surface = [&](int x, int y, uint32_t object, float depth) {
    return x >= 0 && y >= 0 && x < kw && y < kh && key.object.at(x, y) == object &&
           std::abs(key.depth.at(x, y) - depth) <= options.depth_tolerance * depth;
  };
  auto reliable = [&](int x, int y) { return !state || state->at(x, y) == kWarpReliable; };
  assert(frame.base.empty() || (frame.base.width() == frame.sample_camera.width && frame.base.channels() == 3));
  const float* base = frame.base.data().data();
  // project(key.camera, ·) with its per-call constants (the inverse rotation, the focal
  // length's tan) hoisted: the same operations on the same values, so the same bits.
  const quat to_camera = glm::conjugate(key.camera.orientation);
  const vec3 eye = key.camera.position;
  const float focal = focal_length_px(key.camera);
  const float half_w = 0.5f * float(key.camera.width), half_h = 0.5f * float(key.camera.height);

  parallel_for(n, kSampleGrain, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const vec3 c = to_camera * (frame.position[i] - eye);
      const float depth = -c.z;
      const uint32_t object = frame.reflector[i];
      if (!(depth > 0.0f)) {
        out.flag[i] = kReuseDisoccluded;
        continue;
      }
      const vec2 q(half_w + focal * c.x / depth, half_h - focal * c.y / depth);
      const int nx = int(std::floor(q.x)), ny = int(std::floor(q.y));
      if (!same_surface(nx, ny, object, depth)) {
        out.flag[i] = kReuseDisoccluded;
        continue;
      }
      if (!reliable(nx, ny)) {
        const uint8_t st = state->at(nx, ny);
        out.flag[i] = uint8_t(kReuseUnreliable | (st == kWarpCurved ? kReuseCurved : 0) | (st == kWarpEdge ? kReuseEdge : 0));
        continue;
      }
      // blend_error: a reused value likely to be wrong on the display is recomputed.
      const bool gate = mesh && mesh->blend_error < kInf;
      BlendSamples blend;
      auto risky = [&](vec3 value) {
        const float* rgb = base + size_t(frame.pixel[i]) * 3u;  // G-buffer pixel y·width + x
        return blend_risk_exceeds(blend, value, frame.specular[i], vec3(rgb[0], rgb[1], rgb[2]), mesh->blend_error);
      };
      if (mesh && warped_radiance_at(*mesh, q, out.radiance[i], gate ? &blend : nullptr)) {
        if (gate && risky(out.radiance[i])) {
          out.radiance[i] = vec3(0.0f);
          out.flag[i] = uint8_t(kReuseUnreliable | kReuseEdge);
        }
        continue;
      }
      // Bilinear over the usable pixels of the 2×2 around q (the nearest is one of them).
      const float fx = q.x - 0.5f, fy = q.y - 0.5f;
      const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
      const float tx = fx - float(x0), ty = fy - float(y0);
      vec3 sum(0.0f), lo(kInf), hi(-kInf);
      float weight = 0.0f;
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k) {
          const int x = x0 + k, y = y0 + j;
          if (!same_surface(x, y, object, depth) || !reliable(x, y)) continue;
          const float wt = (k ? tx : 1.0f - tx) * (j ? ty : 1.0f - ty);
          if (wt <= 0.0f) continue;
          const vec3 lr(radiance.at(x, y, 0), radiance.at(x, y, 1), radiance.at(x, y, 2));
          sum += wt * lr;
          weight += wt;
          lo = glm::min(lo, key.specular.at(x, y) * lr), hi = glm::max(hi, key.specular.at(x, y) * lr);
          blend.lr[blend.n] = lr, blend.w[blend.n] = wt, ++blend.n;
        }
      // The same edge rule as the mesh's: no blend across a reflected edge.
      const vec3 range = hi - lo;
      const bool edge = mesh && weight > 0.0f && std::max({range.x, range.y, range.z}) > mesh->edge_contrast;
      if (edge && mesh->edge_rule == ReflectedEdgeRule::kRecompute) {
        out.flag[i] = uint8_t(kReuseUnreliable | kReuseEdge);
      } else if (edge) {
        out.radiance[i] = vec3(radiance.at(nx, ny, 0), radiance.at(nx, ny, 1), radiance.at(nx, ny, 2));
      } else if (weight > 0.0f) {
        out.radiance[i] = sum / weight;
        if (gate && risky(out.radiance[i])) {
          out.radiance[i] = vec3(0.0f);
          out.flag[i] = uint8_t(kReuseUnreliable | kReuseEdge);
        }
      } else {
        out.radiance[i] = vec3(radiance.at(nx, ny, 0), radiance.at(nx, ny, 1), radiance.at(nx, ny, 2));
      }
    }
  });
  for (uint8_t f : out.flag) {
    out.disoccluded += (f & kReuseDisoccluded) != 0;
    out.unreliable += (f & kReuseUnreliable) != 0;
    out.curved += (f & kReuseCurved) != 0;
    out.edge += (f & kReuseEdge) != 0;
  }
}

}  // namespace proxima
