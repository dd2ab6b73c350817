// Embree oracle for the visibility maps of Funkhouser's beam tracer (section 4): the map's
// label per pixel center versus the item buffer, split into samples near map edges and
// interior samples, plus a depth check of disagreeing interior labels.
#include "proxima/visibility/oracle.h"

#include <cmath>

#include "proxima/trace/reference_renderer.h"

namespace proxima::visibility {
namespace {

// Whether `poly` passes through `hit` within `tol`: on its plane and inside its
// (convex) outline. Such a label ties in depth with the polygon the ray hit.
bool contains(const InputPolygon& poly, const dvec3& hit, double tol) {
  if (std::abs(poly.plane.distance(hit)) > tol) return false;
  const size_t n = poly.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    const dvec3& a = poly.vertices[i];
    const dvec3 out = glm::cross(poly.vertices[(i + 1) % n] - a, poly.plane.normal);
    const double len = glm::length(out);
    if (len > 0.0 && glm::dot(out, hit - a) > tol * len) return false;
  }
  return true;
}

}  // namespace

OracleCounts& OracleCounts::operator+=(const OracleCounts& o) {
  samples += o.samples;
  agree += o.agree;
  interior += o.interior;
  interior_agree += o.interior_agree;
  occluded_label += o.occluded_label;
  depth_ties += o.depth_ties;
  return *this;
}

OracleCounts compare_with_ray_casts(const VisibilityMap& map, const ModelPolygons& model,
                                    const Scene& scene, const RayScene& rays, const Camera& camera) {
  const ImageU32 labels = rasterize_map(map);
  const ImageU8 near_edge = map_edge_mask(map, 1.0);
  const ItemBuffer item = trace_item_buffer(scene, rays, camera);
  OracleCounts c;
  const dvec3 eye(camera.position);
  const double tie_tol = kSnapTolerance * model.scale;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const uint32_t tri = item.triangle.at(x, y);
      const uint32_t truth = tri == kNoTriangle ? kNone : model.triangle_polygon[tri];
      const uint32_t label = labels.at(x, y);
      const dvec3 hit(item.position.at(x, y, 0), item.position.at(x, y, 1), item.position.at(x, y, 2));
      // A different polygon through the hit point (coplanar overlapping faces, a seam, two
      // faces crossing there) ties in depth with the one Embree reports: either is right.
      const bool tie = label != truth && label != kNone && truth != kNone &&
                       contains(model.polygons[label], hit, tie_tol);
      const bool agree = label == truth || tie;
      ++c.samples;
      c.agree += agree;
      c.depth_ties += tie;
      if (near_edge.at(x, y)) continue;
      ++c.interior;
      c.interior_agree += agree;
      if (agree || label == kNone || truth == kNone) continue;
      // The labeled polygon is occluded if the ray hits something before reaching its plane.
      const Ray ray = ray_through(camera, vec2(float(x) + 0.5f, float(y) + 0.5f));
      const Plane& pl = model.polygons[label].plane;
      const double denom = glm::dot(pl.normal, dvec3(ray.dir));
      if (std::abs(denom) < 1e-12) continue;
      const double t_label = -pl.distance(eye) / denom;
      const double t_hit = glm::length(hit - eye);
      c.occluded_label += t_hit < t_label - 1e-4 * model.scale;
    }
  return c;
}

}  // namespace proxima::visibility
