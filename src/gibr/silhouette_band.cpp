#include "proxima/gibr/silhouette_band.h"

#include <algorithm>
#include <cmath>

#include "proxima/gibr/novel_view.h"

namespace proxima::gibr {

using namespace proxima::visibility;

namespace {

// A pinhole camera in double precision: world point → (pixel x, pixel y, depth).
struct View {
  dvec3 eye, R, U, F;
  double f, cx, cy;
  explicit View(const Camera& c)
      : eye(c.position), R(camera_right(c)), U(camera_up(c)), F(camera_forward(c)), f(focal_length_px(c)),
        cx(0.5 * c.width), cy(0.5 * c.height) {}
  double depth(const dvec3& p) const { return glm::dot(p - eye, F); }
  dvec2 pixel(const dvec3& p) const {
    const dvec3 d = p - eye;
    const double z = glm::dot(d, F);
    return {cx + f * glm::dot(d, R) / z, cy - f * glm::dot(d, U) / z};
  }
  dvec3 sightline(const dvec2& q) const { return F + ((q.x - cx) / f) * R - ((q.y - cy) / f) * U; }
};

// Liang–Barsky: the parameter range [u0, u1] of a + u (b − a) inside the box; false if none.
bool clip_to_box(const dvec2& a, const dvec2& b, const dvec2& lo, const dvec2& hi, double& u0, double& u1) {
  u0 = 0.0;
  u1 = 1.0;
  const dvec2 d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double p = side ? d[axis] : -d[axis];
      const double q = side ? hi[axis] - a[axis] : a[axis] - lo[axis];
      if (p == 0.0) {
        if (q < 0.0) return false;
        continue;
      }
      const double r = q / p;
      if (p < 0.0) u0 = std::max(u0, r);
      else u1 = std::min(u1, r);
    }
  }
  return u0 <= u1;
}

}  // namespace

std::vector<LiftedEdge> lift_silhouettes(const VisibilityMap& map, const Camera& camera, const ModelPolygons& model,
                                         uint32_t photo) {
  const View v(camera);
  std::vector<LiftedEdge> out;
  for (const MapEdge& e : map.edges) {
    if (!e.silhouette || e.source == kImageBorder) continue;
    const dvec2 qa = map.vertices[e.vertex[0]], qb = map.vertices[e.vertex[1]];
    for (uint32_t r : e.region) {
      if (r == kNone || map.regions[r].polygon == kNone) continue;
      const uint32_t p = map.regions[r].polygon;
      const Plane& pl = model.polygons[p].plane;
      LiftedEdge le;
      le.polygon = p;
      le.photo = photo;
      bool ok = true;
      for (int k = 0; k < 2 && ok; ++k) {
        const dvec3 dir = v.sightline(k ? qb : qa);
        const double denom = glm::dot(pl.normal, dir), t = -pl.distance(v.eye) / denom;
        ok = denom != 0.0 && t > 0.0 && std::isfinite(t);
        (k ? le.b : le.a) = v.eye + t * dir;
      }
      if (ok) out.push_back(le);
    }
  }
  return out;
}

std::vector<LiftedEdge> blended_edges(std::span<const LiftedEdge> edges, const RadianceMaps& maps,
                                      const ModelPolygons& model, const vec3& eye, int k) {
  // Per polygon, the photographs of its first k layers (the novel view's ranking).
  std::vector<std::vector<uint32_t>> first(model.polygons.size());
  std::vector<std::pair<float, uint32_t>> keyed;
  for (size_t p = 0; p < model.polygons.size() && p < maps.layers.size(); ++p) {
    rank_layers(maps, model, p, eye, keyed);
    for (size_t r = 0; r < keyed.size() && r < size_t(k); ++r) first[p].push_back(maps.layers[p][keyed[r].second].photo);
  }
  std::vector<LiftedEdge> out;
  for (const LiftedEdge& e : edges)
    if (e.polygon < first.size() && std::find(first[e.polygon].begin(), first[e.polygon].end(), e.photo) != first[e.polygon].end())
      out.push_back(e);
  return out;
}

ImageU8 reprojected_edge_mask(std::span<const LiftedEdge> edges, const Camera& view, const RayScene& rays,
                              double radius, double scale) {
  const View v(view);
  const int W = view.width, H = view.height;
  ImageU8 mask(W, H, 1, 0);
  const double near = std::max(1e-6 * scale, double(view.near));
  const dvec2 lo(-radius, -radius), hi(W + radius, H + radius);
  std::vector<Ray> batch;
  std::vector<dvec2> where;
  auto flush = [&] {
    std::vector<uint8_t> blocked(batch.size(), 0);
    rays.occluded(batch, blocked);
    for (size_t s = 0; s < batch.size(); ++s) {
      if (blocked[s]) continue;
      const dvec2 c = where[s];
      const int x0 = std::max(0, int(std::floor(c.x - radius - 0.5))), x1 = std::min(W - 1, int(std::ceil(c.x + radius)));
      const int y0 = std::max(0, int(std::floor(c.y - radius - 0.5))), y1 = std::min(H - 1, int(std::ceil(c.y + radius)));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double dx = x + 0.5 - c.x, dy = y + 0.5 - c.y;
          if (dx * dx + dy * dy <= radius * radius) mask.at(x, y) = 1;
        }
    }
    batch.clear();
    where.clear();
  };
  for (const LiftedEdge& e : edges) {
    // The part of the edge in front of the near plane.
    dvec3 a = e.a, b = e.b;
    const double za = v.depth(a), zb = v.depth(b);
    if (za < near && zb < near) continue;
    if (za < near) a = a + ((near - za) / (zb - za)) * (b - a);
    else if (zb < near) b = b + ((near - zb) / (za - zb)) * (a - b);
    const double wa = 1.0 / v.depth(a), wb = 1.0 / v.depth(b);  // 1/depth is affine in the image
    const dvec2 pa = v.pixel(a), pb = v.pixel(b);
    double u0, u1;
    if (!clip_to_box(pa, pb, lo, hi, u0, u1)) continue;
    const int n = int(std::ceil(glm::length(pb - pa) * (u1 - u0) / 0.25));
    for (int s = 0; s <= n; ++s) {
      const double u = n == 0 ? u0 : u0 + (u1 - u0) * double(s) / double(n);
      const double t = u * wb / ((1.0 - u) * wa + u * wb);  // the world parameter of image parameter u
      const dvec3 p = a + t * (b - a);
      const dvec3 d = p - v.eye;
      const double dist = glm::length(d);
      Ray r;
      r.origin = vec3(v.eye);
      r.dir = vec3(d / dist);
      r.tmin = 0.0f;
      r.tmax = float(dist * (1.0 - 1e-4) - 1e-4 * scale);
      if (!(r.tmax > 0.0f)) continue;
      batch.push_back(r);
      where.push_back(pa + u * (pb - pa));
      if (batch.size() >= (1u << 18)) flush();
    }
  }
  flush();
  return mask;
}

}  // namespace proxima::gibr
