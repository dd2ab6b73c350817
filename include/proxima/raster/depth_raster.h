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

// Rasterizes every triangle of the objects whose bounds (`bounds`, one per object,
// or empty: computed) meet the frustum into `depth` (−z_cam, +inf where empty; resized to
// the camera). Fills the triangle counts of RasterStats (not the fragment counts or times).
// Throws InputError for an invalid camera.
RasterStats rasterize_depth_serial(const Scene& scene, const Camera& camera, std::span<const Bounds3> bounds,
                                   CullMode cull, ImageF& depth, DepthRasterScratch& scratch);

}  // namespace proxima
