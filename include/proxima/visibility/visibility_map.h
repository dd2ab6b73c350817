// Beam tracing (Funkhouser, section 4, Figure 6) through a winged pair: the visibility map
// of one camera, a planar map on the image plane.
// Conventions: pixel coordinates (DESIGN.md), x right, y down, pixel centers at +0.5; the
// map covers [0, width] × [0, height]. Region polygons have positive shoelace area in
// these coordinates; the region of a map edge's vertex[0] → vertex[1] "left" side is the
// one with positive cross product. Polygon ids as in visibility/polygons.h; kNone =
// background (sightlines leaving the outer box).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/visibility/winged_pair.h"

namespace proxima::visibility {

// Map-edge sources that are not winged-pair edges: the image border.
inline constexpr uint32_t kImageBorder = 0xFFFFFFF0u;

struct MapRegion {
  std::vector<dvec2> vertices;        // convex, positive shoelace area, pixel coordinates
  std::vector<uint32_t> edge_source;  // per boundary edge i → i+1: winged-pair edge or kImageBorder
  uint32_t face = kNone;              // the opaque face seen, or the outer face escaped through
  uint32_t polygon = kNone;           // input polygon of `face`; kNone = background
  uint32_t merged = kNone;            // merged-region id (contiguous regions of one polygon)
};

struct MapEdge {
  uint32_t vertex[2] = {kNone, kNone};
  uint32_t region[2] = {kNone, kNone};  // left, right of vertex[0] → vertex[1]; kNone = none
  uint32_t source = kNone;              // winged-pair edge it lies on, or kImageBorder
  bool silhouette = false;              // occluding contour: source edge's opaque faces all on one
                                        // side of the plane through the eye and the edge
};

struct MapStats {
  size_t beams = 0;             // beams traced (face intersections, opaque or transparent)
  size_t cells_visited = 0;
  size_t faces_culled = 0;      // faces skipped as wholly outside a beam plane
  size_t escaped = 0;           // beams ended as background at a transparent face beyond
                                // the opaque faces' bounding box (nothing left to meet)
  size_t regions = 0;           // final convex regions
  size_t merged_regions = 0;    // after merging contiguous regions of one polygon
  size_t visible_polygons = 0;  // distinct polygons with a region
  size_t silhouette_edges = 0;  // map edges flagged silhouette
  double ms = 0.0;              // wall time of trace_visibility_map
};

struct VisibilityMap {
  int width = 0, height = 0;
  std::vector<dvec2> vertices;
  std::vector<MapEdge> edges;
  std::vector<MapRegion> regions;
  MapStats stats;
};

struct TraceOptions {
  // Skip a boundary face lying wholly outside one plane of the current beam (eye + a region
  // edge) before projecting and clipping it. Same map either way (tested); off = reference.
  bool beam_culling = true;
  // Rejoin the pieces of a face's projection before passing them on: the face's whole
  // projection when the beams entering the cell cover it, convex unions of pieces
  // otherwise (docs/visibility.md). Same labels at every pixel either way (tested); off =
  // every piece traced on separately (the reference).
  bool rejoin = true;
  // End a beam as background at a transparent face beyond the opaque faces' bounding box.
  // Same labels either way (tested); off = traced on to the outer box.
  bool escape = true;
};

// Traces the beams of `camera` through `wp` (built with finalize()); the camera must lie
// inside the outer box (InputError otherwise). The near/far clip distances are ignored:
// the map is exact for every depth > 1e-6 · scale.
VisibilityMap trace_visibility_map(const WingedPair& wp, const Camera& camera, const TraceOptions& options = {});

// Polygon id at every pixel center (1 channel, kNone = background): the region containing
// the center, with the fill rule left edge inclusive, right edge exclusive per row.
ImageU32 rasterize_map(const VisibilityMap& map);

// Shoelace area of a region, pixels² (positive for a well-formed region).
double region_area(const MapRegion& region);

// 1 where a pixel center lies within `radius` pixels of a map edge whose two sides show
// different polygons (or that has only one side), 0 elsewhere.
ImageU8 map_edge_mask(const VisibilityMap& map, double radius = 1.0);

}  // namespace proxima::visibility
