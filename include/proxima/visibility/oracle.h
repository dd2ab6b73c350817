// The Embree oracle for visibility maps (issue 9): the map's polygon at each pixel center
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
  size_t depth_ties = 0;         // samples counted as agreeing because the map's polygon passes
                                 // through the ray's hit point (within kSnapTolerance · scale)

  OracleCounts& operator+=(const OracleCounts& o);
  double agreement_pct() const { return samples ? 100.0 * double(agree) / double(samples) : 100.0; }
  double interior_pct() const { return interior ? 100.0 * double(interior_agree) / double(interior) : 100.0; }
};

// A sample agrees when the map names the polygon Embree hit, or another polygon passing
// through the hit point within the snap tolerance (kSnapTolerance × scale: coplanar
// overlapping faces, seams, faces crossing there — equal depth, either answer is right).
// `map` must be traced for `camera` through the winged pair of `model` (polygons of `scene`);
// `rays` is built from `scene`. The camera's near plane should be closer than any surface.
OracleCounts compare_with_ray_casts(const VisibilityMap& map, const ModelPolygons& model,
                                    const Scene& scene, const RayScene& rays, const Camera& camera);

}  // namespace proxima::visibility
