// Rasterizer benchmark and id-buffer agreement (raster_bench.h).
#include "proxima/raster/raster_bench.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"

namespace proxima {

std::vector<RasterTiming> bench_raster(const Scene& scene, const Camera& camera,
                                       const RasterBenchOptions& options) {
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  std::vector<RasterTiming> timings;
  for (int threads : options.threads) {
    ThreadLimit limit(threads);
    RasterTiming timing;
    timing.threads = threads;
    RasterImages images;  // reused across frames, as a renderer would
    auto median_ms = [&](uint32_t outputs, RasterStats* last) {
      RasterOptions o;
      o.outputs = outputs;
      o.object_bounds = bounds;
      rasterize(scene, camera, o, images, AcceptAllFragments{});  // warm-up
      std::vector<double> samples;
      for (int r = 0; r < options.repetitions; ++r) {
        Stopwatch watch;
        const RasterStats stats = rasterize(scene, camera, o, images, AcceptAllFragments{});
        samples.push_back(watch.elapsed_ms());
        if (last) *last = stats;
      }
      return median(samples);
    };
    timing.depth_id_ms = median_ms(kRasterDepthId, &timing.depth_id_stats);
    timing.gbuffer_ms = median_ms(kRasterGBuffer, nullptr);
    timing.tris_per_s =
        timing.depth_id_ms > 0.0 ? double(scene.triangles.size()) / (timing.depth_id_ms * 1e-3) : 0.0;
    timings.push_back(timing);
  }
  return timings;
}

namespace {

struct RayHit {
  bool inside;   // the ray crosses the triangle (barycentrics in [0, 1], t > 0)
  double depth;  // −z_cam of the ray/plane intersection
};

// Möller–Trumbore in double against the triangle's plane (no early out).
std::optional<RayHit> intersect(const Scene& scene, uint32_t triangle, const Camera& camera, dvec3 dir) {
  const uvec3 idx = scene.triangles[triangle];
  const dvec3 p0(scene.positions[idx.x]), p1(scene.positions[idx.y]), p2(scene.positions[idx.z]);
  const dvec3 origin(camera.position);
  const dvec3 e1 = p1 - p0, e2 = p2 - p0;
  const dvec3 pv = glm::cross(dir, e2);
  const double det = glm::dot(e1, pv);
  if (std::abs(det) < 1e-30) return std::nullopt;
  const double inv = 1.0 / det;
  const dvec3 tv = origin - p0;
  const double u = glm::dot(tv, pv) * inv;
  const dvec3 qv = glm::cross(tv, e1);
  const double v = glm::dot(dir, qv) * inv;
  const double t = glm::dot(e2, qv) * inv;
  const double depth = t * glm::dot(dir, dvec3(camera_forward(camera)));
  return RayHit{u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0, depth};
}

// A center this close (pixels) to both triangles' boundaries lies on their shared edge.
constexpr double kSharedEdgePx = 1e-4;
// Two surfaces whose depths differ by at most this (relative) are one surface: float vertex
// rounding (~1e-7 of a coordinate, coordinates up to ~50× the depth) cannot order them.
constexpr double kCoincidentDepth = 1e-5;

// Screen distance (pixels) from (px, py) to the boundary of the triangle's projection;
// nullopt when a vertex is not in front of the camera.
std::optional<double> edge_distance(const Scene& scene, uint32_t triangle, const Camera& camera, double px,
                                    double py) {
  const glm::dmat3 to_camera(glm::mat3_cast(glm::conjugate(camera.orientation)));
  const double f = focal_length_px(camera);
  const uvec3 idx = scene.triangles[triangle];
  glm::dvec2 s[3];
  for (int i = 0; i < 3; ++i) {
    const dvec3 c = to_camera * (dvec3(scene.positions[idx[i]]) - dvec3(camera.position));
    if (!(-c.z > 0.0)) return std::nullopt;
    s[i] = {0.5 * camera.width + f * c.x / -c.z, 0.5 * camera.height - f * c.y / -c.z};
  }
  double d = std::numeric_limits<double>::infinity();
  const glm::dvec2 q(px, py);
  for (int i = 0; i < 3; ++i) {
    const glm::dvec2 a = s[i], ab = s[(i + 1) % 3] - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(q - a, ab) / len2, 0.0, 1.0) : 0.0;
    d = std::min(d, glm::length(q - (a + t * ab)));
  }
  return d;
}

dvec3 pixel_dir(const Camera& camera, double px, double py) {
  const double f = focal_length_px(camera);
  const dvec3 d((px - 0.5 * camera.width) / f, (0.5 * camera.height - py) / f, -1.0);
  return glm::dmat3(glm::mat3_cast(camera.orientation)) * d;
}

}  // namespace

IdAgreement compare_id_buffers(const Scene& scene, const Camera& camera, const ImageU32& raster,
                               const ImageU32& reference, double edge_px, double depth_epsilon) {
  IdAgreement a;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      ++a.pixels;
      const uint32_t r = raster.at(x, y), e = reference.at(x, y);
      if (r == e) {
        ++a.agree;
        continue;
      }
      const double cx = x + 0.5, cy = y + 0.5;
      // Near an edge: the center is within edge_px of the projected boundary (or, for a
      // triangle reaching behind the camera, inside-ness changes within edge_px).
      auto near_edge = [&](uint32_t t) {
        if (t == kNoTriangle) return false;
        if (const auto d = edge_distance(scene, t, camera, cx, cy)) return *d <= edge_px;
        std::optional<bool> first;
        for (const auto& [dx, dy] :
             {std::pair{0.0, 0.0}, {-1.0, -1.0}, {1.0, -1.0}, {-1.0, 1.0}, {1.0, 1.0}}) {
          const auto hit =
              intersect(scene, t, camera, pixel_dir(camera, cx + dx * edge_px, cy + dy * edge_px));
          const bool in = hit && hit->inside;
          if (first && *first != in) return true;
          first = in;
        }
        return false;
      };
      if (near_edge(r) || near_edge(e)) {
        ++a.edge;
        auto on_boundary = [&](uint32_t t) {
          const auto d = t == kNoTriangle ? std::nullopt : edge_distance(scene, t, camera, cx, cy);
          return d && *d <= kSharedEdgePx;
        };
        if (on_boundary(r) && on_boundary(e)) ++a.on_shared_edge;
        continue;
      }
      if (r != kNoTriangle && e != kNoTriangle) {
        const dvec3 dir = pixel_dir(camera, cx, cy);
        const auto hr = intersect(scene, r, camera, dir), he = intersect(scene, e, camera, dir);
        if (hr && he && hr->inside && he->inside) {
          const double gap = std::abs(hr->depth - he->depth), far = std::max(hr->depth, he->depth);
          if (gap <= depth_epsilon * far) {
            ++a.depth;
            if (gap <= kCoincidentDepth * far) ++a.coincident;
            continue;
          }
        }
      }
      ++a.other;
    }
  return a;
}

}  // namespace proxima
