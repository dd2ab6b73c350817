// Self-check of one visibility map, cheap enough to run on every map: a map that is wrong
// says so instead of passing silently (docs/visibility.md, "Self-check").
//
// Checks, in order (the first failing one names the reason):
// 1. sanity: every region has ≥ 3 finite vertices inside the image (within `slack_px`),
//    positive area, and a polygon id < the model's polygon count or kNone;
// 2. area: the regions' shoelace areas sum to width · height within `area_tolerance`
//    (relative) — a missing region leaves a hole, overlapping regions exceed the image;
// 3. rays: `rays` pixel centers on a fixed jittered grid (deterministic, at least
//    `border_px` from the image border) are located in the map — each must lie in a
//    region and at most one region may contain it deeper than `edge_px`; a center within
//    `edge_px` of a boundary between regions of different labels is skipped, not judged
//    (either label may be right there) — and compared with an Embree ray: a map label of
//    background where Embree hits a polygon, or of another polygon than Embree's, is a
//    mismatch — unless the map's polygon passes through Embree's hit point (coplanar
//    overlapping polygons: either label is right; counted as a tie). More than
//    `max_mismatches` fail the map.
// Beams far above regions are output-sensitivity statistics, not errors: not checked.
#pragma once

#include <cstddef>
#include <string>

#include "proxima/core/camera.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/polygons.h"
#include "proxima/visibility/visibility_map.h"

namespace proxima::visibility {

struct MapCheckOptions {
  int rays = 128;                 // sample pixel centers compared with Embree
  double border_px = 2.0;         // samples keep this far from the image border
  double edge_px = 1.5;           // samples this near a boundary between labels are not judged
  double area_tolerance = 1e-6;   // |Σ region area − image area| / image area
  double slack_px = 1e-3;         // region vertices may lie this far outside the image
  size_t max_mismatches = 0;      // disagreeing samples tolerated
};

struct MapCheck {
  bool pass = true;
  std::string reason;             // one line naming what failed; empty when pass
  double area_ratio = 1.0;        // Σ region area / image area
  size_t samples = 0;             // sample centers judged
  size_t skipped_near_edge = 0;   // sample centers too near a boundary between labels
  size_t uncovered = 0;           // judged centers in no region
  size_t multiply_covered = 0;    // judged centers deep inside more than one region
  size_t mismatches = 0;          // judged centers whose label differs from Embree's polygon
  size_t background_on_geometry = 0;  // of those: map background, Embree hits a polygon
  size_t coplanar_ties = 0;       // judged centers whose two labels are coplanar there (not mismatches)
  double ms = 0.0;                // wall time of the check
};

// `map` traced for `camera` through the winged pair of `model`; `rays` built from the scene
// `model` was extracted from (its triangle ids index model.triangle_polygon). The camera's
// near plane should be closer than any surface. Never throws on a malformed map (that
// fails the check).
MapCheck check_visibility_map(const VisibilityMap& map, const ModelPolygons& model, const RayScene& rays,
                              const Camera& camera, const MapCheckOptions& options = {});

}  // namespace proxima::visibility
