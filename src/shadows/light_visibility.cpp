// Algorithm 5 step 3 (light_visibility.h). Paper: Xie Naiwen, PhD thesis, ch. 3 §3.3
// (../shared/papers/004_d1af2812aec5f9c7.txt, lines 888–925):
//   s        samples[k], one light sample
//   SM       the shadow map: depth image of the occluders seen from s
//   o        a receiver pixel (position p, normal n)
#include "proxima/shadows/light_visibility.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "proxima/core/camera_projection.h"
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

Camera fitted_shadow_map_camera(const LightCameras& cams, vec3 eye, std::span<const vec3> points, float focal_px) {
  const Camera base = light_camera(cams, eye, 16);  // orientation only
  auto whole_field = [&] {
    const int side = std::clamp(int(std::ceil(2.0f * focal_px * std::tan(0.5f * glm::radians(cams.vfov_deg)))), 1,
                                kMaxFittedMapSide);
    return light_camera(cams, eye, side);
  };
  if (points.empty()) return whole_field();
  // Pass 1: the points' rectangle in the light camera's tangent plane; its centre is where
  // the fitted camera looks.
  const quat to_base = glm::conjugate(base.orientation);
  vec2 lo(kInf), hi(-kInf);
  for (const vec3& p : points) {
    const vec3 c = to_base * (p - eye);
    const float depth = -c.z;
    if (!(depth > cams.near)) return whole_field();
    const vec2 t(c.x / depth, c.y / depth);
    lo = glm::min(lo, t);
    hi = glm::max(hi, t);
  }
  const vec2 mid = 0.5f * (lo + hi);
  const vec3 dir = glm::normalize(camera_forward(base) + mid.x * camera_right(base) + mid.y * camera_up(base));
  vec3 up = cams.up;
  if (std::abs(glm::dot(dir, up)) > 0.99f) up = glm::normalize(glm::cross(dir, vec3(1, 0, 0)));
  const Camera turned = look_at(eye, eye + dir, up, 90.0f, 16, 16, cams.near, cams.far);
  // Pass 2: half extents and the farthest depth in the turned camera.
  const quat to_turned = glm::conjugate(turned.orientation);
  vec2 half(0.0f);
  float farthest = 0.0f;
  for (const vec3& p : points) {
    const vec3 c = to_turned * (p - eye);
    const float depth = -c.z;
    if (!(depth > cams.near)) return whole_field();
    half = glm::max(half, vec2(std::abs(c.x), std::abs(c.y)) / depth);
    farthest = std::max(farthest, depth);
  }
  // One texel of margin on each side; a map wider than the cap gets coarser texels.
  float f = focal_px;
  const float widest = std::max(half.x, half.y);
  if (2.0f * (widest * f + 2.0f) > float(kMaxFittedMapSide)) f = (0.5f * float(kMaxFittedMapSide) - 2.0f) / widest;
  const int w = 2 * int(std::ceil(half.x * f + 1.0f)), h = 2 * int(std::ceil(half.y * f + 1.0f));
  const float vfov = 2.0f * glm::degrees(std::atan(0.5f * float(h) / f));
  const float far = std::max(cams.near * 2.0f, farthest * 1.001f + cams.near);
  return look_at(eye, eye + dir, up, vfov, w, h, cams.near, far);
}

namespace {

// Median distance between neighbouring receivers (right and lower neighbours) in the
// tangent plane of `cam`: one receiver footprint seen from the light. 0 without pairs.
float receiver_spacing(const Receivers& r, const Camera& cam) {
  const CameraProjection proj(cam);
  const int w = r.mask.width(), h = r.mask.height();
  std::vector<float> d;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!r.mask.at(x, y)) continue;
      const auto a = proj(rgb_at(r.position, x, y));
      if (!a) continue;
      for (int k = 0; k < 2; ++k) {
        const int nx = x + (k == 0), ny = y + (k == 1);
        if (nx >= w || ny >= h || !r.mask.at(nx, ny)) continue;
        const auto b = proj(rgb_at(r.position, nx, ny));
        if (b) d.push_back(glm::length(a->pixel - b->pixel) / proj.focal);
      }
    }
  if (d.empty()) return 0.0f;
  std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(d.size() / 2), d.end());
  return d[d.size() / 2];
}

// Focal length of every map (ShadowMapOptions' texel density).
float map_focal_px(const LightCameras& cams, const Receivers& receivers, const std::vector<vec3>& samples,
                   const ShadowMapOptions& o) {
  const Camera full = light_camera(cams, samples.empty() ? cams.target + cams.up : samples[samples.size() / 2],
                                   o.resolution);
  float f = focal_length_px(full);
  if (o.footprint_texels > 0.0f && !samples.empty()) {
    vec3 centre(0.0f);
    for (const vec3& s : samples) centre += s;
    const float spacing = receiver_spacing(receivers, light_camera(cams, centre / float(samples.size()), 16));
    if (spacing > 0.0f) f = std::min(f, o.footprint_texels / spacing);
  }
  return f;
}

std::vector<vec3> receiver_points(const Receivers& r) {
  std::vector<vec3> p;
  p.reserve(r.count);
  for (int y = 0; y < r.mask.height(); ++y)
    for (int x = 0; x < r.mask.width(); ++x)
      if (r.mask.at(x, y)) p.push_back(rgb_at(r.position, x, y));
  return p;
}

}  // namespace

LightVisibility shadow_map_visibility(const Scene& occluders, const Receivers& receivers,
                                      const std::vector<vec3>& samples, const LightCameras& cams,
                                      const ShadowMapOptions& options, double* ms, ShadowMapStats* stats) {
  Stopwatch watch;
  ShadowMapStats st;
  const int w = receivers.mask.width(), h = receivers.mask.height();
  LightVisibility v(w, h, int(samples.size()));
  RasterOptions raster;
  raster.outputs = kRasterDepth;
  raster.cull = CullMode::None;  // occluders block light from either side
  const std::vector<Bounds3> bounds = raster_object_bounds(occluders);
  raster.object_bounds = bounds;
  st.focal_px = map_focal_px(cams, receivers, samples, options);
  const std::vector<vec3> points = options.fit_receivers ? receiver_points(receivers) : std::vector<vec3>{};
  std::vector<uint32_t> outside(size_t(h), 0);
  RasterImages map;
  for (size_t k = 0; k < samples.size(); ++k) {
    const vec3 s = samples[k];
    Stopwatch fit;
    const Camera cam = options.fit_receivers ? fitted_shadow_map_camera(cams, s, points, st.focal_px)
                                             : light_camera(cams, s, options.resolution);
    st.fit_ms += fit.elapsed_ms();
    Stopwatch draw;
    const RasterStats rs = rasterize(occluders, cam, raster, map, AcceptAllFragments{});
    st.raster_ms += draw.elapsed_ms();
    st.texels += uint64_t(cam.width) * uint64_t(cam.height);
    st.triangles_drawn += rs.triangles_rasterized;
    Stopwatch test;
    const CameraProjection proj(cam);
    parallel_for(size_t(h), kRows, [&](size_t y0, size_t y1) {
      for (int y = int(y0); y < int(y1); ++y)
        for (int x = 0; x < w; ++x) {
          if (!receivers.mask.at(x, y)) continue;
          const vec3 p = rgb_at(receivers.position, x, y), n = rgb_at(receivers.normal, x, y);
          const vec3 l = s - p;
          const float cos_theta = glm::dot(n, l) / glm::length(l);
          if (!(cos_theta > 0.0f)) continue;  // below the receiver's tangent plane
          const auto q = proj(p);
          int px, py;
          if (!q || !pixel_in(cam, q->pixel, px, py)) {
            set_bit(v, x, y, int(k));  // outside the map: nothing known to block it
            outside[size_t(y)] += options.fit_receivers;
            continue;
          }
          const float tan_theta = std::min(kMaxBiasSlope, std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta)) / cos_theta);
          const float texel = q->depth / proj.focal;
          const float bias = texel * (options.constant_bias + options.slope_bias * tan_theta);
          if (q->depth - bias <= map.depth.at(px, py)) set_bit(v, x, y, int(k));
        }
    });
    st.test_ms += test.elapsed_ms();
  }
  for (uint32_t n : outside) st.receivers_outside += n;
  if (st.receivers_outside > 0)
    std::fprintf(stderr, "shadows: WARNING: %llu receiver tests fell outside their fitted shadow map (taken as lit)\n",
                 static_cast<unsigned long long>(st.receivers_outside));
  st.ms = watch.elapsed_ms();
  if (ms) *ms = st.ms;
  if (stats) *stats = st;
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
