// Depth-only rasterization on the calling thread, for callers that draw many small images
// and run them in parallel themselves (one image per task): no tiles, no binning, no
// attributes. The same transform, clipping, snapping, top-left coverage and
// perspective-correct depth as rasterize() (rasterizer.h) with outputs = kRasterDepth,
// so the depth image is bit-identical to its; each pixel keeps the least depth, which
// does not depend on the draw order.
#pragma once

#include <span>
#include <vector>

#include "proxima/raster/rasterizer.h"

namespace proxima {

// Buffers reused across calls of one task.
struct DepthRasterScratch {
  std::vector<raster_detail::ClipVertex> vertices;
  std::vector<raster_detail::Setup> setups;
};

// The texels a caller will read, one bit per texel, row-major (bit x & 63 of word
// y·words_per_row + x / 64).
struct TexelMask {
  int words_per_row = 0;
  std::vector<uint64_t> bits;
  void reset(int width, int height);  // that size, no texel set
  void set(int x, int y) { bits[size_t(y) * size_t(words_per_row) + size_t(x >> 6)] |= uint64_t(1) << (x & 63); }
};

// Rasterizes every triangle of the objects whose bounds (`bounds`, one per object,
// or empty: computed) meet the frustum into `depth` (−z_cam, +inf where empty; resized to
// the camera). Fills the triangle counts of RasterStats (not the fragment counts or times).
// Throws InputError for an invalid camera.
RasterStats rasterize_depth_serial(const Scene& scene, const Camera& camera, std::span<const Bounds3> bounds,
                                   CullMode cull, ImageF& depth, DepthRasterScratch& scratch);

// The same, but a triangle (needing no clipping) whose pixel box holds no texel of `needed`
// (null: every texel) is culled before its set-up: those texels get the depth above, the
// others may stay empty (+inf). For a caller that reads a few known texels (shadow-map
// lookups of known receivers). Throws InputError when the mask's size is not the camera's.
RasterStats rasterize_depth_serial(const Scene& scene, const Camera& camera, std::span<const Bounds3> bounds,
                                   CullMode cull, const TexelMask* needed, ImageF& depth, DepthRasterScratch& scratch);

}  // namespace proxima
