// Embree oracle for the visibility maps of Funkhouser's beam tracer (section 4): the map's
// label per pixel center versus the item buffer, split into samples near map edges and
// interior samples, plus a depth check of disagreeing interior labels.
#include "proxima/visibility/oracle.h"

#include <algorithm>

#include "proxima/trace/reference_renderer.h"

namespace proxima::visibility {

OracleCounts& OracleCounts::operator+=(const OracleCounts& o) {
  samples += o.samples;
  agree += o.agree;
  interior += o.interior;
  interior_agree += o.interior_agree;
  occluded_label += o.occluded_label;
  ties += o.ties;
  interior_ties += o.interior_ties;
  return *this;
}

bool polygon_through_hit(const ModelPolygons& model, uint32_t polygon, const dvec3& origin, const dvec3& dir,
                         double t_hit) {
  const InputPolygon& poly = model.polygons[polygon];
  const double denom = glm::dot(poly.plane.normal, dir);
  if (std::abs(denom) < 1e-12) return false;
  const double t = -poly.plane.distance(origin) / denom;
  // Float ray-tracing precision plus the snap tolerance (the BSP welds and snaps within it).
  const double snap = kSnapTolerance * model.scale;
  if (!(std::abs(t - t_hit) <= 2e-6 * t_hit + 1e-7 * model.scale + snap)) return false;
  const dvec3 p = origin + t * dir;
  const size_t n = poly.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    const dvec3 a = poly.vertices[i], e = poly.vertices[(i + 1) % n] - a;
    const double len = glm::length(e);
    if (len > 0.0 && glm::dot(glm::cross(e, p - a), poly.plane.normal) / len < -1e-6 * model.scale - snap) return false;
  }
  return true;
}

bool ray_grazes_outline(const ModelPolygons& model, uint32_t polygon, const dvec3& origin, const dvec3& dir) {
  const InputPolygon& poly = model.polygons[polygon];
  const double denom = glm::dot(poly.plane.normal, dir);
  if (std::abs(denom) < 1e-12) return false;
  const double t = -poly.plane.distance(origin) / denom;
  if (!(t > 0.0)) return false;
  const dvec3 p = origin + t * dir;
  const double reach = kSnapTolerance * model.scale + 2e-6 * t;
  const size_t n = poly.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    const dvec3 a = poly.vertices[i], e = poly.vertices[(i + 1) % n] - a;
    const double len2 = glm::dot(e, e);
    const double u = len2 > 0.0 ? std::clamp(glm::dot(p - a, e) / len2, 0.0, 1.0) : 0.0;
    if (glm::length(p - (a + u * e)) <= reach) return true;
  }
  return false;
}

OracleCounts compare_with_ray_casts(const VisibilityMap& map, const ModelPolygons& model,
                                    const Scene& scene, const RayScene& rays, const Camera& camera) {
  const ImageU32 labels = rasterize_map(map);
  const ImageU8 near_edge = map_edge_mask(map, 1.0);
  const ItemBuffer item = trace_item_buffer(scene, rays, camera);
  OracleCounts c;
  const dvec3 eye(camera.position);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const uint32_t tri = item.triangle.at(x, y);
      const uint32_t truth = tri == kNoTriangle ? kNone : model.triangle_polygon[tri];
      const uint32_t label = labels.at(x, y);
      ++c.samples;
      c.agree += label == truth;
      const bool interior = !near_edge.at(x, y);
      c.interior += interior;
      c.interior_agree += interior && label == truth;
      if (label == truth || label == kNone || truth == kNone) continue;
      const Ray ray = ray_through(camera, vec2(float(x) + 0.5f, float(y) + 0.5f));
      const double t_hit = glm::length(dvec3(item.position.at(x, y, 0), item.position.at(x, y, 1),
                                             item.position.at(x, y, 2)) - eye);
      if (polygon_through_hit(model, label, eye, dvec3(ray.dir), t_hit) ||
          ray_grazes_outline(model, label, eye, dvec3(ray.dir)) || ray_grazes_outline(model, truth, eye, dvec3(ray.dir))) {
        ++c.ties;
        c.interior_ties += interior;
        continue;
      }
      if (!interior) continue;
      // The labeled polygon is occluded if the ray hits something before reaching its plane.
      const Plane& pl = model.polygons[label].plane;
      const double denom = glm::dot(pl.normal, dvec3(ray.dir));
      if (std::abs(denom) < 1e-12) continue;
      const double t_label = -pl.distance(eye) / denom;
      c.occluded_label += t_hit < t_label - 1e-4 * model.scale;
    }
  return c;
}

}  // namespace proxima::visibility
