// Algorithm 5 step 3 (light_visibility.h). Paper: Xie Naiwen, PhD thesis, ch. 3 §3.3
// (../shared/papers/004_d1af2812aec5f9c7.txt, lines 888–925):
//   s        samples.points[k], one light sample
//   SM       the shadow map: depth image of the occluders seen from s
//   o        a receiver pixel (position p, normal n)
#include "proxima/shadows/light_visibility.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <span>

#include "proxima/core/camera_projection.h"
#include "proxima/core/image_rgb.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/depthimage/depth_image.h"
#include "proxima/raster/depth_raster.h"
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


}  // namespace

namespace {

// A receiver pixel on the light's emitting side: its index in the image, position and normal.
struct ReceiverPoint {
  int pixel;
  vec3 p, n;
};

// The receivers the light can reach; the others stay unlit, are not tested and are not
// fitted (a map could not hold a point behind the light's plane).
std::vector<ReceiverPoint> receiver_list(const Receivers& r, const AreaLight& light) {
  std::vector<ReceiverPoint> list;
  list.reserve(r.count);
  for (int y = 0; y < r.mask.height(); ++y)
    for (int x = 0; x < r.mask.width(); ++x)
      if (r.mask.at(x, y) && on_emitting_side(light, rgb_at(r.position, x, y)))
        list.push_back({y * r.mask.width() + x, rgb_at(r.position, x, y), rgb_at(r.normal, x, y)});
  return list;
}

// Where the shadow map of `cam` at light sample `s` answers for a receiver: nowhere when the
// receiver faces away from `s` (the sample cannot light it), outside when it projects off
// the map, else at texel (px, py) with its projected depth. The test and the texels a map
// must hold (read_texels_only) both come from here, so they cannot disagree.
struct MapLookup {
  enum Kind : uint8_t { kFacingAway, kOutside, kTexel } kind = kFacingAway;
  int px = 0, py = 0;
  float depth = 0.0f, cos_theta = 0.0f;
};

void map_lookups(const std::vector<ReceiverPoint>& list, size_t i0, size_t i1, vec3 s, const Camera& cam,
                 MapLookup* out) {
  const CameraProjection proj(cam);
  for (size_t i = i0; i < i1; ++i) {
    MapLookup& m = out[i - i0];
    m = MapLookup{};
    const vec3 l = s - list[i].p;
    m.cos_theta = glm::dot(list[i].n, l) / glm::length(l);
    if (!(m.cos_theta > 0.0f)) continue;  // below the receiver's tangent plane
    const auto q = proj(list[i].p);
    m.kind = q && pixel_in(cam, q->pixel, m.px, m.py) ? MapLookup::kTexel : MapLookup::kOutside;
    if (q) m.depth = q->depth;
  }
}

// The texels the lookups read.
void read_texels(std::span<const MapLookup> looks, const Camera& cam, TexelMask& mask) {
  mask.reset(cam.width, cam.height);
  for (const MapLookup& m : looks)
    if (m.kind == MapLookup::kTexel) mask.set(m.px, m.py);
}

// The lookups against the shadow map `depth` of `cam`: lit[i] = 1 where the sample lights
// receiver i. Returns the receivers (facing the sample) that fell outside the map, taken as
// lit.
uint32_t test_receivers(std::span<const MapLookup> looks, const Camera& cam, const ImageF& depth,
                        const ShadowMapOptions& o, uint8_t* lit) {
  const float focal = CameraProjection(cam).focal;
  uint32_t outside = 0;
  for (size_t i = 0; i < looks.size(); ++i) {
    const MapLookup& m = looks[i];
    lit[i] = m.kind == MapLookup::kOutside;  // outside the map: nothing known to block it
    outside += m.kind == MapLookup::kOutside;
    if (m.kind != MapLookup::kTexel) continue;
    const float c = m.cos_theta;
    const float tan_theta = std::min(kMaxBiasSlope, std::sqrt(std::max(0.0f, 1.0f - c * c)) / c);
    const float texel = m.depth / focal;
    const float bias = texel * (o.constant_bias + o.slope_bias * tan_theta);
    lit[i] = m.depth - bias <= depth.at(m.px, m.py);
  }
  return outside;
}

}  // namespace

LightVisibility shadow_map_visibility(const Scene& occluders, const Receivers& receivers,
                                      const LightSamples& light_samples, const LightCameras& cams,
                                      const ShadowMapOptions& options, double* ms, ShadowMapStats* stats) {
  const std::vector<vec3>& samples = light_samples.points;
  Stopwatch watch;
  ShadowMapStats st;
  const int w = receivers.mask.width(), h = receivers.mask.height();
  LightVisibility v(w, h, int(samples.size()));
  const std::vector<Bounds3> bounds = raster_object_bounds(occluders);
  st.focal_px = map_focal_px(cams, receivers, samples, options);
  const std::vector<ReceiverPoint> list = receiver_list(receivers, light_samples.light);
  const size_t count = list.size(), n = samples.size();

  Stopwatch fit;
  std::vector<Camera> map_cams(n);
  {
    std::vector<vec3> points;
    if (options.fit_receivers)
      for (const ReceiverPoint& r : list) points.push_back(r.p);
    for (size_t k = 0; k < n; ++k)
      map_cams[k] = options.fit_receivers ? fitted_shadow_map_camera(cams, samples[k], points, st.focal_px)
                                          : light_camera(cams, samples[k], options.resolution);
  }
  st.fit_ms = fit.elapsed_ms();

  // lit[k·count + i]: sample k lights receiver i. Per sample: triangles set up, receivers
  // outside the map, and the task's raster and test times.
  std::vector<uint8_t> lit(n * count);
  std::vector<uint64_t> drawn(n, 0), outside(n, 0);
  std::vector<double> raster_ms(n, 0.0), test_ms(n, 0.0);
  if (options.per_map_tasks) {
    parallel_for(n, 1, [&](size_t k0, size_t k1) {
      DepthRasterScratch scratch;
      ImageF depth;
      TexelMask read;
      std::vector<MapLookup> looks(count);
      for (size_t k = k0; k < k1; ++k) {
        Stopwatch look;  // counted with the test, which it serves (and the mask)
        map_lookups(list, 0, count, samples[k], map_cams[k], looks.data());
        const double look_ms = look.elapsed_ms();
        Stopwatch draw;
        if (options.read_texels_only) read_texels(looks, map_cams[k], read);
        drawn[k] = rasterize_depth_serial(occluders, map_cams[k], bounds, CullMode::None,
                                          options.read_texels_only ? &read : nullptr, depth, scratch)
                       .triangles_rasterized;
        raster_ms[k] = draw.elapsed_ms();
        Stopwatch test;
        outside[k] = test_receivers(looks, map_cams[k], depth, options, &lit[k * count]);
        test_ms[k] = look_ms + test.elapsed_ms();
      }
    });
  } else {
    RasterOptions raster;
    raster.outputs = kRasterDepth;
    raster.cull = CullMode::None;  // occluders block light from either side
    raster.object_bounds = bounds;
    RasterImages map;
    constexpr size_t kGrain = 2048;  // receivers per parallel chunk
    std::vector<uint32_t> chunk_outside((count + kGrain - 1) / kGrain);
    for (size_t k = 0; k < n; ++k) {
      Stopwatch draw;
      drawn[k] = rasterize(occluders, map_cams[k], raster, map, AcceptAllFragments{}).triangles_rasterized;
      raster_ms[k] = draw.elapsed_ms();
      Stopwatch test;
      parallel_for(chunk_outside.size(), 1, [&](size_t c0, size_t c1) {
        MapLookup looks[kGrain];
        for (size_t c = c0; c < c1; ++c) {
          const size_t i0 = c * kGrain, i1 = std::min(count, i0 + kGrain);
          map_lookups(list, i0, i1, samples[k], map_cams[k], looks);
          chunk_outside[c] = test_receivers({looks, i1 - i0}, map_cams[k], map.depth, options, &lit[k * count + i0]);
        }
      });
      for (uint32_t o : chunk_outside) outside[k] += o;
      test_ms[k] = test.elapsed_ms();
    }
  }
  parallel_for(count, 4096, [&](size_t i0, size_t i1) {
    for (size_t i = i0; i < i1; ++i)
      for (size_t k = 0; k < n; ++k)
        if (lit[k * count + i]) set_bit(v, list[i].pixel % w, list[i].pixel / w, int(k));
  });
  for (size_t k = 0; k < n; ++k) {
    st.texels += uint64_t(map_cams[k].width) * uint64_t(map_cams[k].height);
    st.triangles_drawn += drawn[k];
    if (options.fit_receivers) st.receivers_outside += outside[k];
    st.raster_ms += raster_ms[k];
    st.test_ms += test_ms[k];
  }
  if (st.receivers_outside > 0)
    std::fprintf(stderr, "shadows: WARNING: %llu receiver tests fell outside their fitted shadow map (taken as lit)\n",
                 static_cast<unsigned long long>(st.receivers_outside));
  st.ms = watch.elapsed_ms();
  if (ms) *ms = st.ms;
  if (stats) *stats = st;
  return v;
}

LightVisibility ray_visibility(const RayScene& rays, const Scene& scene, const Receivers& receivers,
                               const LightSamples& light_samples, double* ms) {
  const std::vector<vec3>& samples = light_samples.points;
  Stopwatch watch;
  const int w = receivers.mask.width(), h = receivers.mask.height();
  LightVisibility v(w, h, int(samples.size()));
  const float eps = 1e-4f * scene_bounds(scene).diagonal();
  // Receiver pixels the light can reach, row-major, and their ray origins.
  std::vector<int> pixel;
  std::vector<vec3> origin;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (receivers.mask.at(x, y) && on_emitting_side(light_samples.light, rgb_at(receivers.position, x, y))) {
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
