// Rasterizer benchmark and agreement figures for `proxima bench raster` (docs/journal/raster.md,
// docs/journal/raster.md). Timing is wall-clock, median of repetitions after a warm-up
// frame; agreement compares a rasterized triangle-id buffer with a ray-cast item buffer of
// the same camera.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/scene/scene.h"

namespace proxima {

struct RasterBenchOptions {
  std::vector<int> threads{1, 2};  // thread counts to time (ThreadLimit); ≤ 0 = all cores
  int repetitions = 9;             // timed frames per configuration (median reported)
};

// One thread count's figures.
struct RasterTiming {
  int threads = 0;             // as requested (≤ 0: all cores)
  double depth_id_ms = 0.0;    // median ms per frame, outputs kRasterDepthId
  double gbuffer_ms = 0.0;     // median ms per frame, outputs kRasterGBuffer
  double tris_per_s = 0.0;     // scene triangles / (depth_id_ms / 1000)
  RasterStats depth_id_stats;  // stats of the last depth + id frame
};

// Times depth + id and G-buffer frames of `scene` from `camera` (its width × height),
// one RasterTiming per entry of options.threads, in that order. Object bounds are
// computed once beforehand, as a renderer drawing many frames would.
std::vector<RasterTiming> bench_raster(const Scene& scene, const Camera& camera,
                                       const RasterBenchOptions& options = {});

// Pixel-center agreement between a rasterized id buffer and a reference (ray-cast) one,
// with every disagreement classified by re-intersecting the pixel ray (double precision)
// with both triangles:
//  - edge: the pixel center lies within `edge_px` pixels of an edge of either triangle
//    (fixed-point snapping moves vertices by up to 1/8192 pixel, and Embree's float
//    ray/triangle test is not exact either: ties on edges are arbitrary);
//    of those, `on_shared_edge` counts centers within 1e-4 pixel of both triangles'
//    boundaries: on the edge they share, where either id is right and which one a ray
//    caster reports depends on its traversal (Embree's differs between CPUs: the cornell
//    box's corner edges run exactly through the pixel centers of its square views);
//  - depth: the pixel ray hits both triangles at depths within depth_epsilon·depth;
//  - other: anything else (a real disagreement).
struct IdAgreement {
  size_t pixels = 0;
  size_t agree = 0;
  size_t edge = 0;
  size_t on_shared_edge = 0;  // subset of edge
  size_t depth = 0;
  size_t coincident = 0;      // subset of depth: both surfaces at one depth within float
                              // precision (coplanar overlapping faces): either id is right
  size_t other = 0;

  double agreement_pct() const { return pixels ? 100.0 * double(agree) / double(pixels) : 100.0; }
  // Agreement counting centers on a shared edge and coincident surfaces as agreeing (either
  // id is right there).
  double agreement_with_ties_pct() const {
    return pixels ? 100.0 * double(agree + on_shared_edge + coincident) / double(pixels) : 100.0;
  }
};

// raster and reference: 1-channel id images of camera.width × camera.height.
IdAgreement compare_id_buffers(const Scene& scene, const Camera& camera, const ImageU32& raster,
                               const ImageU32& reference, double edge_px = 1.0 / 64.0,
                               double depth_epsilon = 1e-3);

}  // namespace proxima
