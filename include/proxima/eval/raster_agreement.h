// The rasterizer checked against Embree on every camera of every built-in scene: rasterized
// triangle ids vs the ray-cast item buffer at pixel centers (the rasterizer's acceptance figure).
#pragma once

#include <string>
#include <vector>

#include "proxima/raster/raster_bench.h"

namespace proxima {

struct CameraAgreement {
  std::string scene;
  std::string camera;
  IdAgreement agreement;
};

// One entry per built-in scene camera, rendered at size × size, in registry order.
std::vector<CameraAgreement> raster_agreement_on_builtins(int size);

}  // namespace proxima
