// Where an item buffer's wrongly colored lines can show in a novel view. An item buffer maps
// a photograph pixel straddling a silhouette onto the polygon at its center, so its mixed
// color lands on the surfaces along the *photograph's* silhouette — the occluder's outline
// and the line where the occluder's edge meets the surface behind it. Seen again from a novel
// view those lines lie mostly away from the novel view's own silhouettes. The band of pixels
// near their reprojections is where the paper's claim (Funkhouser, Figure 1) is decided.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/gibr/radiance_map.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/polygons.h"
#include "proxima/visibility/visibility_map.h"

namespace proxima::gibr {

// A silhouette edge of a photograph's visibility map on one side's polygon: the world
// points where the sightlines through the edge's end points meet that polygon's plane (the
// segment between them is the edge on the plane: the plane through the eye and the edge
// cuts it in a straight line).
struct LiftedEdge {
  dvec3 a{0.0}, b{0.0};
  uint32_t polygon = visibility::kNone;
  uint32_t photo = 0;  // the photograph whose map it comes from
};

// The silhouette edges of `map` (the visibility map of `camera`) lifted onto the polygon on
// each side (background sides skipped; an end point whose sightline misses the plane in
// front of the eye drops that side).
std::vector<LiftedEdge> lift_silhouettes(const visibility::VisibilityMap& map, const Camera& camera,
                                         const visibility::ModelPolygons& model, uint32_t photo);

// The edges a novel view at `eye` can show through the blend: those of the photographs among
// the first k layers of the edge's polygon in the novel view's ranking (novel_view.h: the
// polygon's layers in `maps` by the angle at its centroid between the photograph's eye and
// `eye`), in their order.
std::vector<LiftedEdge> blended_edges(std::span<const LiftedEdge> edges, const RadianceMaps& maps,
                                      const visibility::ModelPolygons& model, const vec3& eye, int k);

// 1 where a pixel center of `view` lies within `radius` px of a point of an edge that the
// view sees, else 0. Each edge is sampled at points ≤ 0.25 px apart in the view
// (perspective-correct); a sample counts when it lies in front of the eye, inside the image
// plus `radius`, and no surface of `rays` lies between the eye and it (up to 10⁻⁴ of the
// distance, and 10⁻⁴ · scale before it: the point's own surface is not in the way).
ImageU8 reprojected_edge_mask(std::span<const LiftedEdge> edges, const Camera& view, const RayScene& rays,
                              double radius, double scale);

}  // namespace proxima::gibr
