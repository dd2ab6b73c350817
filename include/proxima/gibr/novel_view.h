// Novel views from radiance maps (Funkhouser, section 2, phase 4; view-dependent texture
// mapping after Debevec et al.): rasterize the model, and per pixel blend the samples of the
// photographs whose directions are closest to the viewing direction.
//
// Per frame, each polygon's layers are ranked by the angle at the polygon's centroid
// between the directions to the photograph's eye and to the novel eye. Per pixel x on
// polygon P (rasterized depth → world point, texel coordinates on P's grid): the first k
// layers in that order with a direct sample at x (bilinear over the layer's 2 × 2 texels
// around x that hold direct samples, weights renormalized) are blended with weights
//   w_i = 1 / (1 − cos θ_i + 1e-7),   θ_i = angle at x between (c_i − x) and (eye − x),
// (≈ 2/θ_i² for small angles: a novel view at a photograph's pose takes that photograph).
// Where no layer has a direct sample, the same over direct and exact-visible (kExtrapolated)
// samples (radiance_map.h); the item buffer's samples are all direct.
// Holes (no layer has such a sample at x): the texel nearest to x, within `hole_radius`
// texels, of the layer whose photograph's eye is nearest to x (the nearest photograph that
// saw P), else of the other layers in ranked order, else — last resort — the nearest kMixed
// sample in ranked order; the pixel is flagged in the unseen mask either way, and stays
// black when nothing is found.
// Antialiasing (`supersample` = s > 1), multisample-style: the model is rasterized at s× the
// resolution, i.e. at the cell centers of a regular s × s grid in each pixel — the sample
// positions of render_reference's supersampling. A pixel whose samples all see one polygon is
// shaded once, at its center (the radiance maps already hold pixel-filtered photograph colors;
// shading every sample would filter them twice); any other pixel (silhouettes, polygon
// boundaries, background) shades each sample and takes their box average (background samples
// black). A pixel is unseen when any point shaded for it is a hole.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/gibr/radiance_map.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/scene/scene.h"

namespace proxima::gibr {

struct NovelViewOptions {
  int k = 3;             // photographs blended per pixel, ≥ 1
  int hole_radius = 32;  // texels searched around a hole
  // Texels: a hole with a kMixed sample but no sample with alpha ≥ kExtrapolated within this
  // reach (in any layer) takes the nearest kMixed one within it before the wide search; 0 = off.
  int mixed_reach = 0;
  int supersample = 1;   // s×s samples per pixel (antialiasing), 1..8 (InputError otherwise)
  // false: the plain path — a pass over the layers per sample kind, every hole searched
  // afresh ring by ring over whole squares; the same bits, for tests and benchmarks of the
  // fast one (both kinds in one pass, layers far from the texel skipped by an integer test,
  // hole fills memoized, ring cells only, rings started at the layer's reach: docs/gibr.md).
  bool fast = true;
};

struct NovelView {
  ImageF color;   // linear RGB, 3 channels; background (nothing rasterized) black
  ImageU8 unseen; // 1 where no photograph's sample covers the pixel's surface point (hole)
  // Pixels with surface (≥ 1 sample on a polygon): total, unseen, unseen whose every hole
  // sample the fill found a color for.
  size_t holes = 0, holes_filled = 0, covered = 0;
  double raster_ms = 0.0, blend_ms = 0.0;
};

// Buffers kept between frames: the fine raster's depth and triangle images. Passing the same
// scratch to successive calls skips their allocation and clearing (every pixel is rewritten);
// the results are the same.
struct NovelViewScratch {
  RasterImages raster;
};

// Polygon p's layers in a frame's order: (−cos of the angle at p's centroid between the
// directions to the layer's photograph and to `eye`, layer index), closest direction first.
void rank_layers(const RadianceMaps& maps, const visibility::ModelPolygons& model, size_t p, const vec3& eye,
                 std::vector<std::pair<float, uint32_t>>& keyed);

// `scene` and `model` as used for the maps (model = extract_polygons(scene)).
NovelView render_novel_view(const Scene& scene, const visibility::ModelPolygons& model, const RadianceMaps& maps,
                            const Camera& camera, const NovelViewOptions& options = {},
                            NovelViewScratch* scratch = nullptr);

}  // namespace proxima::gibr
