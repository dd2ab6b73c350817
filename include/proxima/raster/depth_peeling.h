// Depth peeling (C. Everitt, "Interactive Order-Independent Transparency", NVIDIA 2001)
// built on the rasterizer's fragment test: layer k + 1 keeps, per pixel, the nearest
// fragment behind layer k.
//
// Ordering rule (exact, no epsilon): the fragments of a pixel are ordered by
// (depth, triangle id) lexicographically — the order the depth test itself uses. A
// fragment is behind the previous layer when its (depth, id) is strictly greater than
// the layer's (depth, id) at that pixel; the depth test then picks the smallest of those.
// So every fragment of a pixel appears in exactly one layer, coplanar fragments (equal
// depth) come out one per layer in triangle-id order, and a pixel empty in layer k stays
// empty after it. This is Embree's next_hit ordering (t, geomID, primID) in raster form.
// With min_separation ε > 0 a fragment also needs depth > (1 + ε)·layer depth: fragments
// within ε of the previous layer count as the same surface and are skipped.
#pragma once

#include <vector>

#include "proxima/raster/rasterizer.h"

namespace proxima {

// Fragment test keeping fragments behind a previous layer (depth and triangle images).
struct BehindLayerTest {
  const ImageF& layer_depth;
  const ImageU32& layer_triangle;
  float min_separation = 0.0f;

  bool operator()(const Fragment& f) const {
    const float d = layer_depth.at(f.x, f.y);
    if (min_separation > 0.0f) return f.depth > d * (1.0f + min_separation);
    return f.depth > d || (f.depth == d && f.triangle > layer_triangle.at(f.x, f.y));
  }
};

struct DepthPeelOptions {
  int max_layers = 8;           // layers to peel at most
  float min_separation = 0.0f;  // ε above (relative depth); 0 = exact ordering only
  RasterOptions raster;         // outputs (depth and triangle are always added), culling …
};

// Layers 0, 1, … front to back; stops after max_layers or at the first empty layer (not
// returned). Each layer holds the images of raster.outputs | kRasterDepthId.
std::vector<RasterImages> depth_peel(const Scene& scene, const Camera& camera,
                                     const DepthPeelOptions& options = {});

}  // namespace proxima
