// Depth-based reprojection (thesis ch. 5 §5.4, step 3), as a gather over the new frame's
// reflective samples: deterministic, and each sample gets exactly one answer or a flag.
#include "proxima/reflect/temporal_reprojection.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "proxima/core/camera_projection.h"
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
  // Every sample's value and flag are written below: no fill pass first (resize fills only
  // growth, in the vectors' memory when they have room).
  out.radiance.resize(n);
  out.flag.resize(n);
  out.key_pixel.resize(n);
  assert(frame.base.empty() || (frame.base.width() == frame.sample_camera.width && frame.base.channels() == 3));
  const float* base = frame.base.data().data();
  // Raw rows of the key's images (Image::at's index arithmetic per read, without its
  // channel multiply): the same pixels.
  const uint32_t* key_object = key.object.data().data();
  const float* key_depth = key.depth.data().data();
  const float* key_specular = key.specular.data().data();
  const size_t sw = state ? size_t(state->width()) : 0u;
  const uint8_t* state_px = state ? state->data().data() : nullptr;
  const size_t rw = size_t(radiance.width()), rc = size_t(radiance.channels());
  const float* radiance_px = radiance.data().data();
  auto key_radiance = [&](int x, int y) {
    const float* p = radiance_px + (size_t(y) * rw + size_t(x)) * rc;
    return vec3(p[0], p[1], p[2]);
  };
  // The pixel's WarpState, kWarpReliable without a state image.
  auto warp_state = [&](int x, int y) {
    return state_px ? state_px[size_t(y) * sw + size_t(x)] : uint8_t(kWarpReliable);
  };
  const CameraProjection project_to_key(key.camera);
  // blend_error: a reused value likely to be wrong on the display is recomputed.
  const bool gate = mesh && mesh->blend_error < kInf;
  // No channel range exceeds an infinite (or NaN) edge_contrast: the range is not needed then.
  const bool edge_test = mesh && mesh->edge_contrast < kInf;
  const bool edge_recompute = mesh && mesh->edge_rule == ReflectedEdgeRule::kRecompute;
  // Flag counts: per chunk, then summed (integer sums: any order gives the same totals).
  std::atomic<uint64_t> disoccluded{0}, unreliable{0}, curved{0}, edges{0};

  parallel_for(n, kSampleGrain, [&](size_t b, size_t e) {
    uint64_t n_disoccluded = 0, n_unreliable = 0, n_curved = 0, n_edge = 0;
    for (size_t i = b; i < e; ++i) {
      const std::optional<Projection> projected = project_to_key(frame.position[i]);
      const uint32_t object = frame.reflector[i];
      vec3& value = out.radiance[i];
      uint8_t& flag = out.flag[i];
      value = vec3(0.0f);
      flag = kReuseOk;
      out.key_pixel[i] = kNoKeyPixel;
      if (!projected) {  // behind the key camera
        flag = kReuseDisoccluded, ++n_disoccluded;
        continue;
      }
      const float depth = projected->depth;
      const float tolerance = options.depth_tolerance * depth;
      auto same_surface = [&](int x, int y) {
        if (!(x >= 0 && y >= 0 && x < kw && y < kh)) return false;
        const size_t at = size_t(y) * size_t(kw) + size_t(x);
        return key_object[at] == object && std::abs(key_depth[at] - depth) <= tolerance;
      };
      const vec2 q = projected->pixel;
      const int nx = int(std::floor(q.x)), ny = int(std::floor(q.y));
      if (!same_surface(nx, ny)) {
        flag = kReuseDisoccluded, ++n_disoccluded;
        continue;
      }
      out.key_pixel[i] = uint32_t(ny) * uint32_t(kw) + uint32_t(nx);
      if (const uint8_t st = warp_state(nx, ny); st != kWarpReliable) {
        flag = uint8_t(kReuseUnreliable | (st == kWarpCurved ? kReuseCurved : 0) |
                       (st == kWarpEdge ? kReuseEdge : 0));
        ++n_unreliable, n_curved += st == kWarpCurved, n_edge += st == kWarpEdge;
        continue;
      }
      BlendSamples blend;
      auto risky = [&](vec3 v) {
        const float* rgb = base + size_t(frame.pixel[i]) * 3u;  // G-buffer pixel y·width + x
        return blend_risk_exceeds(blend, v, frame.specular[i], vec3(rgb[0], rgb[1], rgb[2]),
                                  mesh->blend_error);
      };
      auto recompute_edge = [&] {  // keeps the value: the recompute observes its error
        flag = uint8_t(kReuseUnreliable | kReuseEdge | kReuseKept);
        ++n_unreliable, ++n_edge;
      };
      if (mesh && warped_radiance_at(*mesh, q, value, gate ? &blend : nullptr)) {
        if (gate && risky(value)) recompute_edge();
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
          if (!same_surface(x, y) || warp_state(x, y) != kWarpReliable) continue;
          const float wt = (k ? tx : 1.0f - tx) * (j ? ty : 1.0f - ty);
          if (wt <= 0.0f) continue;
          const vec3 lr = key_radiance(x, y);
          sum += wt * lr;
          weight += wt;
          if (edge_test) {
            const float s = key_specular[size_t(y) * size_t(kw) + size_t(x)];
            lo = glm::min(lo, s * lr), hi = glm::max(hi, s * lr);
          }
          blend.lr[blend.n] = lr, blend.w[blend.n] = wt, ++blend.n;
        }
      // The same edge rule as the mesh's: no blend across a reflected edge.
      const vec3 range = hi - lo;
      const bool edge =
          edge_test && weight > 0.0f && std::max({range.x, range.y, range.z}) > mesh->edge_contrast;
      if (edge && edge_recompute) {
        flag = uint8_t(kReuseUnreliable | kReuseEdge);
        ++n_unreliable, ++n_edge;
      } else if (edge) {
        value = key_radiance(nx, ny);
      } else if (weight > 0.0f) {
        value = sum / weight;
        if (gate && risky(value)) recompute_edge();
      } else {
        value = key_radiance(nx, ny);
      }
    }
    disoccluded += n_disoccluded, unreliable += n_unreliable, curved += n_curved, edges += n_edge;
  });
  out.disoccluded = disoccluded, out.unreliable = unreliable, out.curved = curved, out.edge = edges;
}

}  // namespace proxima
