#include "proxima/gibr/lens_mapping.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "proxima/core/error.h"

namespace proxima::gibr {

using namespace proxima::visibility;

namespace {

// Point queries on a visibility map at any image position: the polygon whose region holds
// the point, and whether a map edge passes within a radius of it. Regions and edges are
// listed per cell of kCell × kCell pixels by their bounding boxes (edges' grown by the
// largest radius asked).
class MapLocator {
 public:
  static constexpr int kCell = 4;

  MapLocator(const VisibilityMap& map, double max_radius)
      : map_(map), gw_((map.width + kCell - 1) / kCell), gh_((map.height + kCell - 1) / kCell),
        regions_(size_t(gw_) * size_t(gh_)), edges_(size_t(gw_) * size_t(gh_)) {
    for (uint32_t r = 0; r < map.regions.size(); ++r) {
      const MapRegion& R = map.regions[r];
      if (R.polygon == kNone || R.vertices.size() < 3) continue;
      dvec2 lo(INFINITY), hi(-INFINITY);
      for (const dvec2& v : R.vertices) lo = glm::min(lo, v), hi = glm::max(hi, v);
      add(regions_, lo, hi, r);
    }
    for (uint32_t k = 0; k < map.edges.size(); ++k) {
      const MapEdge& e = map.edges[k];
      if (e.source == kImageBorder || polygon_of(e.region[0]) == polygon_of(e.region[1])) continue;
      const dvec2 a = map.vertices[e.vertex[0]], b = map.vertices[e.vertex[1]];
      add(edges_, glm::min(a, b) - dvec2(max_radius), glm::max(a, b) + dvec2(max_radius), k);
    }
  }

  // kNone: background, or p outside the image.
  uint32_t polygon_at(const dvec2& p) const {
    const std::vector<uint32_t>* cell = at(regions_, p);
    if (!cell) return kNone;
    for (uint32_t r : *cell)
      if (contains(map_.regions[r], p)) return map_.regions[r].polygon;
    return kNone;
  }

  // A silhouette edge (all_boundaries: any edge between different polygons) within r of p
  // (r at most the constructor's max_radius).
  bool near_edge(const dvec2& p, double r, bool all_boundaries) const {
    const std::vector<uint32_t>* cell = at(edges_, p);
    if (!cell) return false;
    for (uint32_t k : *cell) {
      const MapEdge& e = map_.edges[k];
      if (!all_boundaries && !e.silhouette) continue;
      const dvec2 a = map_.vertices[e.vertex[0]], d = map_.vertices[e.vertex[1]] - a;
      const double len2 = glm::dot(d, d);
      const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
      if (glm::length(p - (a + t * d)) <= r) return true;
    }
    return false;
  }

 private:
  uint32_t polygon_of(uint32_t region) const { return region == kNone ? kNone - 1 : map_.regions[region].polygon; }

  // Closed convex region (positive shoelace area: interior on the left of each edge).
  static bool contains(const MapRegion& R, const dvec2& q) {
    const size_t n = R.vertices.size();
    for (size_t k = 0; k < n; ++k) {
      const dvec2 a = R.vertices[k], e = R.vertices[(k + 1) % n] - a, r = q - a;
      if (e.x * r.y - e.y * r.x < 0.0) return false;
    }
    return true;
  }

  void add(std::vector<std::vector<uint32_t>>& cells, dvec2 lo, dvec2 hi, uint32_t id) const {
    const int x0 = std::max(0, int(std::floor(lo.x / kCell))), x1 = std::min(gw_ - 1, int(std::floor(hi.x / kCell)));
    const int y0 = std::max(0, int(std::floor(lo.y / kCell))), y1 = std::min(gh_ - 1, int(std::floor(hi.y / kCell)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) cells[size_t(y) * size_t(gw_) + size_t(x)].push_back(id);
  }

  const std::vector<uint32_t>* at(const std::vector<std::vector<uint32_t>>& cells, const dvec2& p) const {
    if (!(p.x >= 0.0 && p.y >= 0.0 && p.x < map_.width && p.y < map_.height)) return nullptr;
    return &cells[size_t(int(p.y) / kCell) * size_t(gw_) + size_t(int(p.x) / kCell)];
  }

  const VisibilityMap& map_;
  int gw_, gh_;
  std::vector<std::vector<uint32_t>> regions_, edges_;
};

}  // namespace

LensLabels vismap_lens_pixel_polygons(const VisibilityMap& map, const Camera& camera, const Lens& lens,
                                      bool exclude_all_boundaries, int samples) {
  const int W = map.width, H = map.height;
  if (camera.width != W || camera.height != H) fail_input("lens mapping: the map's size differs from its camera's");
  if (samples < 0 || samples > 8) fail_input("lens mapping: samples per pixel side must be in 0..8");
  std::vector<dvec2> center(size_t(W) * size_t(H));
  std::vector<double> radius(center.size());
  double max_radius = 0.0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t i = size_t(y) * size_t(W) + size_t(x);
      const dvec2 c(x + 0.5, y + 0.5);
      center[i] = undistort_pixel(camera, lens, c);
      radius[i] = undistorted_radius(camera, lens, c, std::sqrt(0.5)) + 1e-9;
      max_radius = std::max(max_radius, radius[i]);
    }
  const MapLocator loc(map, max_radius);
  // The undistorted pixel square lies in the map's image (its corners do, to rounding: the
  // square's sides bulge by far less than a pixel's width).
  auto square_in_map = [&](int x, int y) {
    for (const dvec2 c : {dvec2(x, y), dvec2(x + 1, y), dvec2(x, y + 1), dvec2(x + 1, y + 1)}) {
      const dvec2 u = undistort_pixel(camera, lens, c);
      if (!(u.x >= -1e-9 && u.y >= -1e-9 && u.x <= W + 1e-9 && u.y <= H + 1e-9)) return false;
    }
    return true;
  };
  LensLabels out;
  out.labels = ImageU32(W, H, 1, kNone);
  UnmixInputs& u = out.unmix;
  u.samples = std::max(1, samples);
  u.centers = ImageU32(W, H, 1, kNone);
  u.touched = ImageU8(W, H, 1, 0);
  u.on_any_edge = ImageU8(W, H, 1, 1);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t i = size_t(y) * size_t(W) + size_t(x);
      const dvec2 p = center[i];
      const double r = radius[i];
      if (!square_in_map(x, y)) continue;
      const uint32_t polygon = loc.polygon_at(p);
      const bool touched = loc.near_edge(p, r, exclude_all_boundaries);
      u.centers.at(x, y) = polygon;
      u.touched.at(x, y) = touched;
      u.on_any_edge.at(x, y) = exclude_all_boundaries ? touched : loc.near_edge(p, r, true);
      if (!touched) out.labels.at(x, y) = polygon;
    }
  if (samples == 0) return out;
  const int s = samples;
  u.fine = ImageU32(W * s, H * s, 1, kNone);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (!u.touched.at(x, y)) continue;
      for (int j = 0; j < s; ++j)
        for (int k = 0; k < s; ++k) {
          const dvec2 q(x + (k + 0.5) / s, y + (j + 0.5) / s);
          u.fine.at(x * s + k, y * s + j) = loc.polygon_at(undistort_pixel(camera, lens, q));
        }
    }
  return out;
}

ImageU32 itembuffer_lens_pixel_polygons(const RayScene& rays, const ModelPolygons& model, const Camera& camera,
                                        const Lens& lens) {
  const int W = camera.width, H = camera.height;
  std::vector<Ray> sightlines;
  std::vector<size_t> pixel;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const dvec2 p = undistort_pixel(camera, lens, {x + 0.5, y + 0.5});
      if (!(p.x >= 0.0 && p.y >= 0.0 && p.x < W && p.y < H)) continue;
      sightlines.push_back(ray_through(camera, vec2(p)));
      pixel.push_back(size_t(y) * size_t(W) + size_t(x));
    }
  std::vector<Hit> hits(sightlines.size());
  rays.intersect(sightlines, hits);
  ImageU32 out(W, H, 1, kNone);
  for (size_t k = 0; k < hits.size(); ++k)
    if (hits[k].valid()) out.data()[pixel[k]] = model.triangle_polygon[hits[k].triangle];
  return out;
}

}  // namespace proxima::gibr
