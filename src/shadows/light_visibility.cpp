// Algorithm 5 step 3 (light_visibility.h). Paper: Xie Naiwen, PhD thesis, ch. 3 §3.3
// (../shared/papers/004_d1af2812aec5f9c7.txt, lines 888–925):
//   s        samples[k], one light sample
//   SM       the shadow map: depth image of the occluders seen from s
//   o        a receiver pixel (position p, normal n)
#include "proxima/shadows/light_visibility.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "proxima/core/image_rgb.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/depthimage/depth_image.h"
#include "proxima/raster/rasterizer.h"

namespace proxima {

LightVisibility::LightVisibility(int w, int h, int n_samples)
    : width(w), height(h), samples(n_samples), words((n_samples + 63) / 64),
      bits(size_t(w) * size_t(h) * size_t((n_samples + 63) / 64), 0) {}

int LightVisibility::lit_count(int x, int y) const {
  const size_t base = (size_t(y) * size_t(width) + size_t(x)) * size_t(words);
  int n = 0;
  for (int k = 0; k < words; ++k) n += std::popcount(bits[base + size_t(k)]);
  return n;
}

namespace {

constexpr size_t kRows = 8;  // receiver rows per parallel chunk


void set_bit(LightVisibility& v, int x, int y, int s) {
  v.bits[(size_t(y) * size_t(v.width) + size_t(x)) * size_t(v.words) + size_t(s >> 6)] |= uint64_t(1) << (s & 63);
}

}  // namespace

LightVisibility shadow_map_visibility(const Scene& occluders, const Receivers& receivers,
                                      const std::vector<vec3>& samples, const LightCameras& cams,
                                      const ShadowMapOptions& options, double* ms) {
  Stopwatch watch;
  const int w = receivers.mask.width(), h = receivers.mask.height();
  LightVisibility v(w, h, int(samples.size()));
  RasterOptions raster;
  raster.outputs = kRasterDepth;
  raster.cull = CullMode::None;  // occluders block light from either side
  const std::vector<Bounds3> bounds = raster_object_bounds(occluders);
  raster.object_bounds = bounds;
  RasterImages map;
  for (size_t k = 0; k < samples.size(); ++k) {
    const vec3 s = samples[k];
    const Camera cam = light_camera(cams, s, options.resolution);
    rasterize(occluders, cam, raster, map, AcceptAllFragments{});
    const float f = focal_length_px(cam);
    parallel_for(size_t(h), kRows, [&](size_t y0, size_t y1) {
      for (int y = int(y0); y < int(y1); ++y)
        for (int x = 0; x < w; ++x) {
          if (!receivers.mask.at(x, y)) continue;
          const vec3 p = rgb_at(receivers.position, x, y), n = rgb_at(receivers.normal, x, y);
          const vec3 l = s - p;
          const float cos_theta = glm::dot(n, l) / glm::length(l);
          if (!(cos_theta > 0.0f)) continue;  // below the receiver's tangent plane
          const auto q = project(cam, p);
          int px, py;
          if (!q || !pixel_in(cam, q->pixel, px, py)) {
            set_bit(v, x, y, int(k));  // outside the map: nothing known to block it
            continue;
          }
          const float tan_theta = std::min(kMaxBiasSlope, std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta)) / cos_theta);
          const float texel = q->depth / f;
          const float bias = texel * (options.constant_bias + options.slope_bias * tan_theta);
          if (q->depth - bias <= map.depth.at(px, py)) set_bit(v, x, y, int(k));
        }
    });
  }
  if (ms) *ms = watch.elapsed_ms();
  return v;
}

LightVisibility ray_visibility(const RayScene& rays, const Scene& scene, const Receivers& receivers,
                               const std::vector<vec3>& samples, double* ms) {
  Stopwatch watch;
  const int w = receivers.mask.width(), h = receivers.mask.height();
  LightVisibility v(w, h, int(samples.size()));
  const float eps = 1e-4f * scene_bounds(scene).diagonal();
  // Receiver pixels, row-major, and their ray origins.
  std::vector<int> pixel;
  std::vector<vec3> origin;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (receivers.mask.at(x, y)) {
        pixel.push_back(y * w + x);
        origin.push_back(rgb_at(receivers.position, x, y) + eps * rgb_at(receivers.normal, x, y));
      }
  std::vector<Ray> batch(pixel.size());
  std::vector<uint8_t> blocked(pixel.size());
  std::vector<uint8_t> facing(pixel.size());
  for (size_t k = 0; k < samples.size(); ++k) {
    const vec3 s = samples[k];
    parallel_for(pixel.size(), 4096, [&](size_t i0, size_t i1) {
      for (size_t i = i0; i < i1; ++i) {
        const int x = pixel[i] % w, y = pixel[i] / w;
        const vec3 d = s - origin[i];
        facing[i] = glm::dot(rgb_at(receivers.normal, x, y), d) > 0.0f;
        Ray& r = batch[i];
        r.origin = origin[i];
        r.dir = d;
        r.tmin = 0.0f;
        r.tmax = facing[i] ? 1.0f - eps / std::max(eps, glm::length(d)) : 0.0f;
      }
    });
    rays.occluded(batch, blocked);
    for (size_t i = 0; i < pixel.size(); ++i)
      if (facing[i] && !blocked[i]) set_bit(v, pixel[i] % w, pixel[i] / w, int(k));
  }
  if (ms) *ms = watch.elapsed_ms();
  return v;
}

}  // namespace proxima
