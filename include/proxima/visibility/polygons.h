// Input polygons of exact visibility: the scene's triangles, with edge-adjacent coplanar
// triangles of one object merged greedily into convex polygons (docs/visibility.md).
// Polygon ids label the opaque faces of the winged-pair structure and the regions of the
// visibility map; triangle_polygon maps Embree's triangle ids onto them.
#pragma once

#include <cstdint>
#include <vector>

#include "proxima/core/math.h"
#include "proxima/scene/scene.h"

namespace proxima::visibility {

using glm::dvec2;

inline constexpr uint32_t kNone = 0xFFFFFFFFu;  // no polygon / face / cell / edge

// A plane dot(normal, x) + offset = 0; normal unit. Positive side = the side normal points to.
struct Plane {
  dvec3 normal{0.0, 0.0, 1.0};
  double offset = 0.0;

  double distance(const dvec3& p) const { return glm::dot(normal, p) + offset; }
};

struct InputPolygon {
  std::vector<dvec3> vertices;  // convex, ≥ 3, counter-clockwise seen from the front (normal side)
  Plane plane;                  // through the vertices, normal from the winding
  uint32_t object = 0;          // scene object id
  std::vector<uint32_t> triangles;  // scene triangle ids merged into it
};

struct ModelPolygons {
  std::vector<InputPolygon> polygons;
  std::vector<uint32_t> triangle_polygon;  // per scene triangle: polygon id
  std::vector<vec3> welded_positions;      // per scene vertex: its welded position (an input
                                           // position, the first of its weld group)
  double scale = 1.0;                      // diagonal of the polygons' bounding box, meters (> 0)
};

// The snap tolerance, relative to the model scale: vertices closer than it are welded into
// one (unwelded seams of real content: vertices 1e-5..1e-4 m apart on a 30–200 m level),
// polygons whose vertices all lie within it of one plane share that plane in the BSP, and
// the oracle counts a polygon within it of the ray's hit as a depth tie.
inline constexpr double kSnapTolerance = 1e-5;

// Welds the scene's vertices (kSnapTolerance), then merges each object's edge-adjacent
// triangles (shared welded vertices) whose planes agree
// to 1e-6 relative to the model scale into convex polygons, greedily in triangle order;
// collinear vertices are dropped. Every triangle belongs to exactly one polygon.
ModelPolygons extract_polygons(const Scene& scene);

// The scene with every vertex at its welded position (model = extract_polygons(scene)): the
// geometry the polygons, the winged pair and so the visibility map are exact for. It differs
// from the input by at most the snap tolerance; the oracle compares the map against it.
Scene welded_scene(const Scene& scene, const ModelPolygons& model);

// Twice the area vector of a planar polygon (Newell): its direction is the normal of the
// counter-clockwise winding, its length twice the area.
dvec3 newell_normal(const std::vector<dvec3>& loop);

}  // namespace proxima::visibility
