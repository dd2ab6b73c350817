// Self-check of a visibility map: sanity of its regions, their areas against the image, and
// a sparse deterministic set of Embree rays against the map's labels (map_check.h).
#include "proxima/visibility/map_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/visibility/oracle.h"

namespace proxima::visibility {
namespace {

std::string fmt(const char* format, double a = 0, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c, d);
  return buf;
}

std::string polygon_name(uint32_t polygon) {
  return polygon == kNone ? std::string("background") : "polygon " + std::to_string(polygon);
}

// Regions binned by bounding box on a coarse grid over the image, for point location.
struct RegionGrid {
  int nx = 1, ny = 1;
  double cell_w = 1.0, cell_h = 1.0;
  std::vector<uint32_t> offset, index;

  RegionGrid(const VisibilityMap& map, int cells_x, int cells_y) : nx(cells_x), ny(cells_y) {
    cell_w = double(map.width) / nx;
    cell_h = double(map.height) / ny;
    std::vector<std::vector<uint32_t>> bins(size_t(nx * ny));
    for (uint32_t r = 0; r < map.regions.size(); ++r) {
      const auto& v = map.regions[r].vertices;
      if (v.empty()) continue;
      dvec2 lo = v[0], hi = v[0];
      for (const dvec2& p : v) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
      const int x0 = bin(lo.x / cell_w, nx), x1 = bin(hi.x / cell_w, nx);
      const int y0 = bin(lo.y / cell_h, ny), y1 = bin(hi.y / cell_h, ny);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) bins[size_t(y * nx + x)].push_back(r);
    }
    offset.push_back(0);
    for (const auto& b : bins) {
      index.insert(index.end(), b.begin(), b.end());
      offset.push_back(uint32_t(index.size()));
    }
  }

  // Bin of a coordinate in cell units, clamped to [0, n − 1]; NaN (a malformed region,
  // already failed by the sanity check) → 0.
  static int bin(double v, int n) {
    const double c = std::floor(v);
    if (!(c >= 0.0)) return 0;
    return c >= double(n - 1) ? n - 1 : int(c);
  }

  template <typename F>
  void for_each(dvec2 p, F&& f) const {
    const int x = bin(p.x / cell_w, nx), y = bin(p.y / cell_h, ny);
    const size_t b = size_t(y * nx + x);
    for (uint32_t i = offset[b]; i < offset[b + 1]; ++i) f(index[i]);
  }
};

// Smallest signed distance (pixels) from p to the region's edges: > 0 inside (regions are
// counter-clockwise with positive shoelace area, inside = left of every edge).
double inside_distance(const std::vector<dvec2>& v, dvec2 p) {
  double d = 1e300;
  for (size_t i = 0; i < v.size(); ++i) {
    const dvec2 a = v[i], b = v[(i + 1) % v.size()], e = b - a;
    const double len = std::sqrt(e.x * e.x + e.y * e.y);
    if (len <= 0.0) continue;
    d = std::min(d, (e.x * (p.y - a.y) - e.y * (p.x - a.x)) / len);
  }
  return d;
}

}  // namespace

MapCheck check_visibility_map(const VisibilityMap& map, const ModelPolygons& model, const RayScene& rays,
                              const Camera& camera, const MapCheckOptions& o) {
  Stopwatch watch;
  MapCheck c;
  auto fail = [&](std::string reason) {
    if (c.pass) c.reason = std::move(reason);
    c.pass = false;
  };
  const double W = map.width, H = map.height;
  if (map.width <= 0 || map.height <= 0) {
    fail("map has no pixels");
    c.ms = watch.elapsed_ms();
    return c;
  }

  // 1. Sanity of every region; 2. area.
  double area = 0.0;
  for (size_t r = 0; r < map.regions.size(); ++r) {
    const MapRegion& reg = map.regions[r];
    if (reg.polygon != kNone && reg.polygon >= model.polygons.size()) {
      fail("region " + std::to_string(r) + " is labeled polygon " + std::to_string(reg.polygon) + ", the model has " +
           std::to_string(model.polygons.size()));
      continue;
    }
    if (reg.vertices.size() < 3) {
      fail("region " + std::to_string(r) + " has " + std::to_string(reg.vertices.size()) + " vertices");
      continue;
    }
    for (const dvec2& p : reg.vertices)
      if (!(p.x >= -o.slack_px && p.x <= W + o.slack_px && p.y >= -o.slack_px && p.y <= H + o.slack_px)) {
        fail("region " + std::to_string(r) + " has a vertex outside the image" + fmt(" (%.6g, %.6g)", p.x, p.y));
        break;
      }
    const double a = region_area(reg);
    if (!(a > -o.area_tolerance * W * H)) fail("region " + std::to_string(r) + fmt(" has negative area %.6g px²", a));
    area += a;
  }
  c.area_ratio = area / (W * H);
  if (c.pass && !(std::abs(c.area_ratio - 1.0) <= o.area_tolerance))
    fail(fmt(c.area_ratio < 1.0 ? "area: the regions cover %.6f%% of the image (holes)"
                                : "area: the regions cover %.6f%% of the image (overlaps)",
             100.0 * c.area_ratio));

  // 3. Sparse rays on a jittered grid of gx × gy cells over the image minus its border.
  const double bx0 = o.border_px, by0 = o.border_px, bw = W - 2.0 * o.border_px, bh = H - 2.0 * o.border_px;
  if (o.rays > 0 && bw >= 1.0 && bh >= 1.0) {
    const int gx = std::max(1, int(std::lround(std::sqrt(double(o.rays) * bw / bh))));
    const int gy = std::max(1, (o.rays + gx - 1) / gx);
    const int bins_x = std::clamp(int(std::sqrt(double(map.regions.size()) * W / H)), 1, 64);
    const int bins_y = std::clamp(int(double(bins_x) * H / W) + 1, 1, 64);
    const RegionGrid grid(map, bins_x, bins_y);
    const vec3 forward = camera.orientation * vec3(0.0f, 0.0f, -1.0f);
    std::string example;
    for (int j = 0; j < gy; ++j)
      for (int i = 0; i < gx && j * gx + i < o.rays; ++i) {
        Pcg32 rng(derive_seed(0x5e1fc4ec, uint64_t(j * gx + i)));
        const double px = std::floor(bx0 + (double(i) + rng.next_float()) * bw / gx) + 0.5;
        const double py = std::floor(by0 + (double(j) + rng.next_float()) * bh / gy) + 0.5;
        const dvec2 p(std::min(px, W - 0.5), std::min(py, H - 0.5));
        // Regions containing p (d ≥ 0), deep inside (d ≥ edge_px) or near it (|d| < edge_px).
        size_t contain = 0, deep = 0;
        bool near_other = false;  // a region of another label within edge_px
        uint32_t label = kNone;
        bool labeled = false;
        grid.for_each(p, [&](uint32_t r) {
          const MapRegion& reg = map.regions[r];
          if (reg.vertices.size() < 3) return;
          const double d = inside_distance(reg.vertices, p);
          if (d <= -o.edge_px) return;
          contain += d >= 0.0;
          deep += d >= o.edge_px;
          if (!labeled) {
            label = reg.polygon;
            labeled = true;
          } else if (reg.polygon != label) {
            near_other = true;
          }
        });
        if (deep > 1) {
          ++c.samples;
          ++c.multiply_covered;
          continue;
        }
        if (near_other || (contain == 0 && labeled)) {
          ++c.skipped_near_edge;  // on a boundary between labels: either may be right
          continue;
        }
        ++c.samples;
        if (contain == 0) {
          ++c.uncovered;
          continue;
        }
        Ray ray = ray_through(camera, vec2(float(p.x), float(p.y)));
        const float cos_axis = glm::dot(ray.dir, forward);
        ray.tmin = camera.near / cos_axis;
        ray.tmax = camera.far / cos_axis;
        const Hit hit = rays.intersect(ray);
        const uint32_t truth = hit.valid() && hit.triangle < model.triangle_polygon.size()
                                   ? model.triangle_polygon[hit.triangle]
                                   : kNone;
        if (label == truth) continue;
        if (label != kNone && truth != kNone && polygon_through_hit(model, label, dvec3(ray.origin), dvec3(ray.dir), double(hit.t))) {
          ++c.coplanar_ties;
          continue;
        }
        ++c.mismatches;
        if (label == kNone) ++c.background_on_geometry;
        if (example.empty())
          example = fmt("pixel (%.0f, %.0f): ", std::floor(p.x), std::floor(p.y)) + "map " + polygon_name(label) +
                    ", Embree " + polygon_name(truth);
      }
    if (c.uncovered > 0 || c.multiply_covered > 0)
      fail("rays: " + std::to_string(c.uncovered) + " sample pixels in no region, " +
           std::to_string(c.multiply_covered) + " in more than one (of " + std::to_string(c.samples) + ")");
    if (c.mismatches > o.max_mismatches)
      fail("rays: " + std::to_string(c.mismatches) + " of " + std::to_string(c.samples) +
           " sample pixels disagree with Embree (" + std::to_string(c.background_on_geometry) +
           " background where Embree hits geometry; e.g. " + example + ")");
  }
  c.ms = watch.elapsed_ms();
  return c;
}

}  // namespace proxima::visibility
