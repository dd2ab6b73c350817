// Depth peeling on the fragment test (depth_peeling.h; Everitt 2001).
#include "proxima/raster/depth_peeling.h"

#include <algorithm>

namespace proxima {

std::vector<RasterImages> depth_peel(const Scene& scene, const Camera& camera,
                                     const DepthPeelOptions& options) {
  RasterOptions raster = options.raster;
  raster.outputs |= kRasterDepthId;
  raster.depth_test = true;
  std::vector<RasterImages> layers;
  for (int k = 0; k < options.max_layers; ++k) {
    RasterImages layer;
    RasterStats stats;
    if (layers.empty()) {
      stats = rasterize(scene, camera, raster, layer, AcceptAllFragments{});
    } else {
      const RasterImages& previous = layers.back();
      stats = rasterize(scene, camera, raster, layer,
                        BehindLayerTest{previous.depth, previous.triangle, options.min_separation});
    }
    if (stats.fragments_written == 0) break;
    layers.push_back(std::move(layer));
  }
  return layers;
}

}  // namespace proxima
