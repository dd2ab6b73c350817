#include "proxima/reflect/hit_shading.h"
#include "proxima/reflect/ssr_reflection.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/box_probe.h"
#include "proxima/scene/light.h"

namespace proxima {

namespace {

// Depth tolerance of the plane and cell tests, relative to the depth.
constexpr float kDepthEps = 1e-5f;
// Barycentric slack when the plane crossing is taken as a point of the pixel's triangle.
constexpr float kBaryEps = 1e-3f;

// Triangles whose front side faces away from the camera (their plane has the camera behind it).
std::vector<uint8_t> back_facing(const Scene& scene, vec3 eye) {
  std::vector<uint8_t> out(scene.triangles.size(), 0);
  parallel_for(out.size(), 4096, [&](size_t b, size_t e) {
    for (size_t t = b; t < e; ++t) {
      const vec3 p0 = scene.positions[scene.triangles[t][0]];
      out[t] = glm::dot(triangle_normal(scene, uint32_t(t)), eye - p0) < 0.0f;
    }
  });
  return out;
}

// Level l + 1 from level l: min of fronts, max of backs over each 2×2 block.
void reduce_level(const ImageF& front, const ImageF& back, ImageF& f2, ImageF& b2) {
  const int w = (front.width() + 1) / 2, h = (front.height() + 1) / 2;
  f2 = ImageF(w, h, 1, kInf);
  b2 = ImageF(w, h, 1, -kInf);
  parallel_for(size_t(h), 16, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < w; ++x) {
        float f = kInf, b = -kInf;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int sx = 2 * x + dx, sy = 2 * y + dy;
            if (sx >= front.width() || sy >= front.height()) continue;
            f = std::min(f, front.at(sx, sy));
            b = std::max(b, back.at(sx, sy));
          }
        f2.at(x, y) = f;
        b2.at(x, y) = b;
      }
  });
}

// The point of the ray's screen line at parameter u (pixel coordinates, depth).
struct ScreenLine {
  vec2 p0, d;       // pixel position at u = 0 and its change over [0, 1]
  float iz0, diz;   // 1 / depth at u = 0 and its change
  vec2 at(float u) const { return p0 + u * d; }
  float depth(float u) const { return 1.0f / (iz0 + u * diz); }
};

// Signed distance of world point `p` from the plane of triangle `t`, positive on the camera's side.
struct PixelPlane {
  vec3 n{0.0f};
  float c = 0.0f;
  float distance(vec3 p) const { return glm::dot(n, p) - c; }
};
PixelPlane plane_of(const Scene& scene, uint32_t t, vec3 eye) {
  PixelPlane pl;
  const vec3 p0 = scene.positions[scene.triangles[t][0]];
  pl.n = triangle_normal(scene, t);
  if (glm::dot(pl.n, eye - p0) < 0.0f) pl.n = -pl.n;
  pl.c = glm::dot(pl.n, p0);
  return pl;
}

// Barycentrics (Embree's) of `p` in triangle `t`, or false when p is outside it.
bool barycentrics_of(const Scene& scene, uint32_t t, vec3 p, float& u, float& v) {
  const vec3 a = scene.positions[scene.triangles[t][0]], b = scene.positions[scene.triangles[t][1]],
             c = scene.positions[scene.triangles[t][2]];
  const vec3 e1 = b - a, e2 = c - a, q = p - a;
  const float d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const float q1 = glm::dot(q, e1), q2 = glm::dot(q, e2), den = d11 * d22 - d12 * d12;
  if (!(std::abs(den) > 0.0f)) return false;
  u = (d22 * q1 - d12 * q2) / den;
  v = (d11 * q2 - d12 * q1) / den;
  return u >= -kBaryEps && v >= -kBaryEps && u + v <= 1.0f + kBaryEps;
}

// Confidence factor of a hit at pixel (x, y): 1 inside, fading to 0 at the image border.
float edge_factor(const SsrDepth& d, int x, int y, float fade) {
  const int w = d.camera.width, h = d.camera.height;
  const float band = fade * float(std::min(w, h));
  if (!(band > 0.0f)) return 1.0f;
  const float dist = std::min(std::min(float(x) + 0.5f, float(w - x) - 0.5f), std::min(float(y) + 0.5f, float(h - y) - 0.5f));
  return std::clamp(dist / band, 0.0f, 1.0f);
}

// The level-0 decision at a pixel the pyramid could not skip: the ray against the pixel's
// surface plane over its stretch [ua, ub] of the line.
SsrHit pixel_hit(const Scene& scene, const SsrDepth& d, const ScreenLine& line, vec3 origin, vec3 dir, int x, int y,
                 float ua, float ub, bool came_from_front, const SsrOptions& o, bool& in_front) {
  SsrHit h;
  const uint32_t t = d.triangle.at(x, y);
  const PixelPlane pl = plane_of(scene, t, d.camera.position);
  auto world = [&](float u) { return unproject(d.camera, line.at(u), line.depth(u)); };
  const float tol = kDepthEps * line.depth(ub);
  const float sa = pl.distance(world(ua)), sb = pl.distance(world(ub));
  in_front = sa > -tol && sb > -tol;
  if (in_front) return h;
  h.triangle = t;
  h.u = d.barycentric.at(x, y, 0);
  h.v = d.barycentric.at(x, y, 1);
  const float toward = glm::dot(pl.n, dir);
  if (toward < 0.0f) {
    const float tp = -pl.distance(origin) / toward;
    float u = 0.0f, v = 0.0f;
    if (tp > 0.0f && barycentrics_of(scene, t, origin + tp * dir, u, v)) {
      h.u = std::clamp(u, 0.0f, 1.0f);
      h.v = std::clamp(v, 0.0f, 1.0f - h.u);
    }
  }
  const bool entered_here = sa > -tol;
  h.outcome = entered_here || came_from_front ? SsrOutcome::Hit : SsrOutcome::Hidden;
  h.confidence = h.outcome == SsrOutcome::Hit ? edge_factor(d, x, y, o.edge_fade) : 0.0f;
  return h;
}

}  // namespace

void validate(const SsrOptions& o) {
  require_in_range(o.max_steps, 1, 65536, "ssr max_steps");
  require_in_range(o.edge_fade, 0.0f, 0.5f, "ssr edge_fade");
  if (!(o.min_thickness > 0.0f) || !std::isfinite(o.min_thickness))
    fail_input("ssr min_thickness: must be a positive number");
}

SsrDepth build_ssr_depth(const Scene& scene, const Camera& camera, float min_thickness,
                         std::span<const Bounds3> object_bounds) {
  SsrDepth d;
  d.camera = camera;
  Stopwatch w;
  RasterOptions ro;
  ro.outputs = kRasterDepthId | kRasterBarycentric;
  ro.object_bounds = object_bounds;
  RasterImages g = rasterize(scene, camera, ro);
  d.triangle = std::move(g.triangle);
  d.barycentric = std::move(g.barycentric);
  d.gbuffer_ms = w.elapsed_ms();
  w.restart();
  // Back faces only: the nearest back face behind each pixel bounds the visible surface's thickness.
  const std::vector<uint8_t> back = back_facing(scene, camera.position);
  RasterOptions bo;
  bo.outputs = kRasterDepth;
  bo.object_bounds = object_bounds;
  RasterImages bimg;
  rasterize(scene, camera, bo, bimg, [&](const Fragment& f) { return back[f.triangle] != 0; });
  if (bimg.depth.width() != camera.width) bimg.depth = ImageF(camera.width, camera.height, 1, kInf);
  d.backface_ms = w.elapsed_ms();
  w.restart();
  ImageF front = std::move(g.depth), backd(camera.width, camera.height, 1, -kInf);
  for (size_t i = 0; i < front.data().size(); ++i) {
    const float f = front.data()[i], b = bimg.depth.data()[i];
    if (!std::isfinite(f)) continue;
    backd.data()[i] = b > f * (1.0f + kDepthEps) ? b : f * (1.0f + min_thickness);
  }
  d.front.push_back(std::move(front));
  d.back.push_back(std::move(backd));
  while (d.front.back().width() > 1 || d.front.back().height() > 1) {
    ImageF f2, b2;
    reduce_level(d.front.back(), d.back.back(), f2, b2);
    d.front.push_back(std::move(f2));
    d.back.push_back(std::move(b2));
  }
  d.pyramid_ms = w.elapsed_ms();
  return d;
}

SsrHit trace_ssr_ray(const Scene& scene, const SsrDepth& d, vec3 origin, vec3 dir, float max_distance,
                     const SsrOptions& o) {
  SsrHit miss;
  const Camera& cam = d.camera;
  const vec3 fwd = camera_forward(cam);
  const float z0 = glm::dot(origin - cam.position, fwd), dz = glm::dot(dir, fwd);
  const float near = cam.near * 1.01f;
  if (!(z0 > near)) return miss;
  float t1 = max_distance;
  bool clipped = false;
  if (dz < 0.0f && (z0 - near) / -dz < t1) {
    t1 = (z0 - near) / -dz;
    clipped = true;
  }
  const std::optional<Projection> a = project(cam, origin), b = project(cam, origin + t1 * dir);
  if (!a || !b) return miss;
  ScreenLine line{a->pixel, b->pixel - a->pixel, 1.0f / a->depth, 1.0f / b->depth - 1.0f / a->depth};
  const float W = float(cam.width), H = float(cam.height);
  float u_end = 1.0f;
  for (int k = 0; k < 2; ++k) {
    const float lim = k == 0 ? W : H, p = line.p0[k], dp = line.d[k];
    if (p + dp > lim) u_end = std::min(u_end, (lim - p) / dp);
    if (p + dp < 0.0f) u_end = std::min(u_end, -p / dp);
  }
  const bool leaves = clipped || u_end < 1.0f;
  const float len_px = glm::length(line.d);
  const float bias = 1e-3f / std::max(len_px, 1e-3f);  // a thousandth of a pixel past a cell's edge
  const int top = int(d.front.size()) - 1;
  float u = 0.0f;
  int level = 0;
  bool from_front = true;
  SsrHit h;
  for (h.steps = 0; h.steps < o.max_steps; ++h.steps) {
    if (u >= u_end) {
      h.outcome = leaves ? SsrOutcome::OffScreen : SsrOutcome::Exhausted;
      return h;
    }
    const vec2 p = line.at(u);
    const float size = float(1 << level);
    const ImageF& fl = d.front[size_t(level)];
    const int cx = std::clamp(int(std::floor(p.x / size)), 0, fl.width() - 1);
    const int cy = std::clamp(int(std::floor(p.y / size)), 0, fl.height() - 1);
    float u_next = u_end;
    if (line.d.x > 0.0f) u_next = std::min(u_next, (float(cx + 1) * size - line.p0.x) / line.d.x);
    if (line.d.x < 0.0f) u_next = std::min(u_next, (float(cx) * size - line.p0.x) / line.d.x);
    if (line.d.y > 0.0f) u_next = std::min(u_next, (float(cy + 1) * size - line.p0.y) / line.d.y);
    if (line.d.y < 0.0f) u_next = std::min(u_next, (float(cy) * size - line.p0.y) / line.d.y);
    u_next = std::max(u_next, u);
    const float za = line.depth(u), zb = line.depth(u_next);
    const float zmin = std::min(za, zb), zmax = std::max(za, zb);
    const float f = fl.at(cx, cy), bk = d.back[size_t(level)].at(cx, cy);
    bool front_of = zmax <= f * (1.0f + kDepthEps), behind = !front_of && zmin > bk;
    if (!front_of && !behind) {
      if (level > 0) {
        --level;
        continue;
      }
      bool in_front = false;
      SsrHit hit = pixel_hit(scene, d, line, origin, dir, cx, cy, u, u_next, from_front, o, in_front);
      if (!in_front) {
        hit.steps = h.steps + 1;
        return hit;
      }
      front_of = true;
    }
    from_front = front_of;
    u = u_next + bias;
    level = std::min(level + 1, top);
  }
  h.outcome = SsrOutcome::StepLimit;
  return h;
}

SsrReflections render_ssr_reflections(const Scene& scene, const ReflectionFrame& frame, const SsrOptions& o,
                                      const SsrFallback& fallback, std::span<const Bounds3> object_bounds) {
  validate(o);
  SsrReflections out;
  const SsrDepth depth = build_ssr_depth(scene, frame.sample_camera, o.min_thickness, object_bounds);
  Stopwatch w;
  const size_t n = frame.sample_count();
  out.radiance.assign(n, vec3(0.0f));
  out.confidence.assign(n, 0.0f);
  const float max_distance = std::max(frame.scene_diagonal, 1e-6f);
  std::vector<uint32_t> outcome_counts(n * 5, 0), fallback_rays(n, 0), steps(n, 0);
  std::vector<double> conf_sum(n, 0.0);
  parallel_for(n, 64, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      vec3 sum(0.0f);
      double csum = 0.0;
      for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r) {
        const vec3 dir = frame.direction[r];
        const SsrHit h = trace_ssr_ray(scene, depth, frame.origin[i], dir, max_distance, o);
        ++outcome_counts[i * 5 + size_t(h.outcome)];
        steps[i] += uint32_t(h.steps);
        vec3 l(0.0f);
        if (h.confidence > 0.0f)
          l += h.confidence * shade_reflected_point(scene, h.triangle, h.u, h.v, -dir, frame.area_light_samples);
        if (h.confidence < 1.0f) {
          ++fallback_rays[i];
          const vec3 fb = fallback.map
                              ? box_probe_lookup(*fallback.map, scene.environment, frame.origin[i], dir, fallback.box).color
                              : environment_radiance(scene.environment, dir);
          l += (1.0f - h.confidence) * fb;
        }
        sum += l;
        csum += h.confidence;
      }
      const float rays = float(frame.first_ray[i + 1] - frame.first_ray[i]);
      out.radiance[i] = sum / rays;
      out.confidence[i] = float(csum / double(rays));
      conf_sum[i] = csum;
    }
  });
  SsrStats& st = out.stats;
  st.samples = n;
  st.rays = frame.direction.size();
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 5; ++k) st.outcome_rays[k] += outcome_counts[i * 5 + size_t(k)];
    st.fallback_rays += fallback_rays[i];
    st.fallback_samples += fallback_rays[i] > 0;
    st.steps += steps[i];
    st.confidence_sum += conf_sum[i];
  }
  st.gbuffer_ms = depth.gbuffer_ms;
  st.backface_ms = depth.backface_ms;
  st.pyramid_ms = depth.pyramid_ms;
  st.trace_ms = w.elapsed_ms();
  return out;
}

}  // namespace proxima
