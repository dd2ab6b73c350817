// Spatial subdivision (Funkhouser, section 3): a BSP over the input polygons, built directly
// as a winged-pair cell complex. docs/visibility.md documents the heuristic and tolerances.
#pragma once

#include <cstddef>

#include "proxima/visibility/polygons.h"
#include "proxima/visibility/winged_pair.h"

namespace proxima::visibility {

struct BspOptions {
  int candidates = 16;         // polygon planes scored per split (evenly spaced over the cell's)
  int largest = 8;             // plus this many of the cell's largest-area fragments
  double split_weight = 4.0;   // score = split_weight · fragments split + |front − back|
  double epsilon = 1e-8;       // plane-side tolerance for vertices not made on the plane,
                               // relative to the model scale (docs/visibility.md)
  double box_margin = 0.25;    // outer box = polygon bounds grown by this × scale on each side
};

struct BspStats {
  size_t polygons = 0;
  size_t splits = 0;              // BSP nodes (cells split by a polygon plane)
  size_t fragments_split = 0;     // polygon fragments cut by a split plane
  size_t rejected_planes = 0;     // split attempts inconsistent at their tolerance (each retry counts)
  size_t unplaced_fragments = 0;  // fragments that could not be put on a face (degenerate)
  size_t sealed_cells = 0;        // cells no plane cuts consistently, made opaque (conservative)
  size_t sealed_fragments = 0;    // the fragments they held
  double sealed_extent = 0.0;     // largest sealed cell's bounding-box diagonal (meters)
  size_t aux_splits = 0;          // splits by auxiliary planes (around near-degenerate spots)
  size_t shifted_splits = 0;      // splits by a fragment's plane moved by ≤ 256 · epsilon (its
                                  // own plane cut the cell inconsistently or left no face)
  size_t displaced_fragments = 0; // fragments carved into the nearest parallel face of their
                                  // cell (their own plane missed the cell by > tolerance)
  double build_ms = 0.0;
};

// Builds the winged pair of the polygons inside an outer box. Every cell is convex, every
// face convex, labeled opaque (with the polygon it lies on) or transparent; opaque faces
// tile the polygons. Never throws on degenerate input (coplanar, duplicate, sliver,
// T-junction polygons): what cannot be placed consistently is counted in stats.
WingedPair build_winged_pair(const ModelPolygons& model, const BspOptions& options = {},
                             BspStats* stats = nullptr);

}  // namespace proxima::visibility
