// The Embree oracle for visibility maps: the map's polygon at each pixel center
// against the polygon of the ray-traced item buffer's triangle.
#pragma once

#include <cstddef>

#include "proxima/core/camera.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/polygons.h"
#include "proxima/visibility/visibility_map.h"

namespace proxima::visibility {

struct OracleCounts {
  size_t samples = 0;            // pixel centers compared
  size_t agree = 0;              // same polygon (or both background)
  size_t interior = 0;           // samples farther than 1 px from any map edge between polygons
  size_t interior_agree = 0;
  size_t occluded_label = 0;     // interior samples whose map polygon lies behind the ray's hit
  size_t ties = 0;               // disagreeing samples where the map's polygon passes through the
                                 // ray's hit point (coplanar overlapping polygons: either is right)
                                 // or the ray grazes the outline of the map's or Embree's polygon
                                 // within the snap tolerance (an edge the snapping moved)
  size_t interior_ties = 0;      // of those, interior samples

  OracleCounts& operator+=(const OracleCounts& o);
  double agreement_pct() const { return samples ? 100.0 * double(agree) / double(samples) : 100.0; }
  double interior_pct() const { return interior ? 100.0 * double(interior_agree) / double(interior) : 100.0; }
  // The same counting coplanar ties as agreeing.
  double agreement_with_ties_pct() const {
    return samples ? 100.0 * double(agree + ties) / double(samples) : 100.0;
  }
  double interior_with_ties_pct() const {
    return interior ? 100.0 * double(interior_agree + interior_ties) / double(interior) : 100.0;
  }
};

// True when `polygon` passes through the point at distance t_hit along the ray (origin,
// unit dir): the ray meets its plane there within float ray-tracing precision plus the snap
// tolerance (2e-6 · t_hit + 1e-7 · model.scale + kSnapTolerance · model.scale), inside its
// outline (within 1e-6 · model.scale + the snap tolerance): the BSP welds vertices and
// snaps planes within kSnapTolerance, so polygons that close tie in depth.
bool polygon_through_hit(const ModelPolygons& model, uint32_t polygon, const dvec3& origin, const dvec3& dir,
                         double t_hit);

// True when the ray (origin, unit dir) passes within the snap tolerance (kSnapTolerance ·
// model.scale, plus 2e-6 · t of float ray-tracing precision) of the outline of `polygon`,
// measured where it meets the polygon's plane (at distance t): welding and plane snapping
// move a polygon's edges by up to that much, so a sightline grazing an edge may see either
// side of it (docs/visibility.md, "What the map is exact for").
bool ray_grazes_outline(const ModelPolygons& model, uint32_t polygon, const dvec3& origin, const dvec3& dir);

// `map` must be traced for `camera` through the winged pair of `model` (polygons of `scene`);
// `rays` is built from `scene`. The camera's near plane should be closer than any surface.
OracleCounts compare_with_ray_casts(const VisibilityMap& map, const ModelPolygons& model,
                                    const Scene& scene, const RayScene& rays, const Camera& camera);

}  // namespace proxima::visibility
