// Tiled software rasterizer with a programmable per-fragment test.
//
// Exact like hardware:
//  - vertices are transformed to clip space (X, Y, W) with W = −z_cam (view depth) and
//    X/W, Y/W = continuous pixel coordinates (DESIGN.md: pixel centers at +0.5, row 0 on
//    top); triangles are clipped homogeneously against the near and far planes, and
//    against a guard band of kRasterGuardBandPx pixels around the viewport for the sides;
//  - screen coordinates are snapped to fixed point with 12 fractional bits (1/4096
//    pixel, raster_frame.h); coverage is
//    decided by exact integer edge functions at pixel centers (x + 0.5, y + 0.5) with the
//    top-left fill rule, so triangles sharing an edge cover each pixel center once;
//  - depth and barycentrics are interpolated perspective-correctly (1/W, u/W, v/W are
//    planes in screen space).
// Depth test: a fragment passes when (depth, triangle id) is lexicographically smaller
// than what the pixel holds, so equal depths resolve to the lower triangle id whatever
// the draw or thread order. The fragment test then decides keep/discard before the write.
// Parallel over 64×64 screen tiles after binning; the output is bit-identical for any
// thread count.
#pragma once

#include <cstdint>
#include <span>
#include <utility>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/core/parallel.h"
#include "proxima/raster/fragment.h"
#include "proxima/scene/scene.h"

namespace proxima {

// Output buffers, chosen per call as a bit set.
enum RasterOutput : uint32_t {
  kRasterDepth = 1u << 0,        // ImageF, 1 channel: −z_cam, +inf where empty
  kRasterTriangle = 1u << 1,     // ImageU32, 1 channel: triangle id, kNoTriangle where empty
  kRasterBarycentric = 1u << 2,  // ImageF, 2 channels: Embree (u, v), 0 where empty
  kRasterNormal = 1u << 3,       // ImageF, 3 channels: unit world shading normal on the
                                 // camera's side (as trace/), 0 where empty
  kRasterDiffuse = 1u << 4,      // ImageF, 3 channels: linear RGB diffuse albedo (texture
                                 // applied), optionally lit (RasterOptions::direct_light)
  kRasterObject = 1u << 5,       // ImageU32, 1 channel: object id, kNoObject where empty
};
inline constexpr uint32_t kRasterDepthId = kRasterDepth | kRasterTriangle;
// G-buffer preset: everything a deferred shader or an image-based technique needs.
inline constexpr uint32_t kRasterGBuffer =
    kRasterDepth | kRasterTriangle | kRasterBarycentric | kRasterNormal | kRasterDiffuse | kRasterObject;
inline constexpr uint32_t kNoObject = 0xFFFFFFFFu;

enum class CullMode {
  None,  // draw both sides
  Back,  // drop triangles whose snapped screen winding is clockwise as seen by the camera
         // (scene triangles are counter-clockwise from the front)
};

// A run of consecutive triangle ids of one object, first .. first + count − 1, and a range
// of vertex indices first_vertex .. first_vertex + vertex_count − 1 that holds every vertex
// of those triangles (only those are transformed).
struct TriangleRun {
  uint32_t first = 0, count = 0;
  uint32_t first_vertex = 0, vertex_count = 0;
};

struct RasterOptions {
  uint32_t outputs = kRasterDepthId;  // RasterOutput bits
  CullMode cull = CullMode::None;
  // false: every covered fragment goes to the fragment test and, if kept, overwrites the
  // pixel (coverage counting).
  bool depth_test = true;
  // kRasterDiffuse: docs/shading.md without shadows or reflections (combine_shading with
  // reflected = 0) — emission + (1 − s)·albedo·(ambient + Σ E/π) over the point lights,
  // unshadowed (area lights are left to techniques that sample them) — instead of the
  // bare albedo.
  bool direct_light = false;
  bool fragment_barycentrics = false;  // fill Fragment::u, v for the fragment test
  // What to draw (at most one non-empty; all empty = the whole scene):
  std::span<const uint32_t> objects;    // object ids, drawn in this order
  std::span<const uint32_t> triangles;  // triangle ids, drawn in this order
  // Runs of triangles (e.g. a culled list of mesh blocks), drawn in this order: the same
  // as `triangles` listing their ids, without the per-triangle list. Needs objects.
  std::span<const TriangleRun> triangle_runs;
  // Per-object world bounds for view-frustum culling (size == scene.objects.size(), e.g.
  // from raster_object_bounds()); empty = computed in the call (one pass over vertices).
  std::span<const Bounds3> object_bounds;
};

// What a call did (meshoptimizer-style statistics; counts are exact, times wall-clock).
struct RasterStats {
  uint64_t objects_drawn = 0;         // objects that survived view-frustum culling
  uint64_t objects_culled = 0;        // objects whose bounds lie outside the frustum
  uint64_t triangles_submitted = 0;   // triangles of the drawn objects / the id list
  uint64_t triangles_culled = 0;      // back faces, degenerate after snapping, or outside
  uint64_t triangles_clipped = 0;     // triangles that went through homogeneous clipping
  uint64_t triangles_rasterized = 0;  // screen triangles binned (clipping may split one)
  uint64_t fragments_tested = 0;      // fragments that passed the depth test
  uint64_t fragments_written = 0;     // fragments the fragment test kept
  double geometry_ms = 0.0;           // transform, clip, setup, binning
  double raster_ms = 0.0;             // tiles: coverage, depth, fragment test, resolve
};

// Images a call fills, one per RasterOutput bit requested (the others are left alone).
// An image already of the camera's size (and channel count) is reused in place.
struct RasterImages {
  ImageF depth;
  ImageU32 triangle;
  ImageF barycentric;
  ImageF normal;
  ImageF diffuse;
  ImageU32 object;
};

// World bounds of every object, for RasterOptions::object_bounds.
std::vector<Bounds3> raster_object_bounds(const Scene& scene);

// Rasterizes the scene (or the subset in `options`) seen from `camera` at the camera's
// width × height into `out`, calling test(const Fragment&) → bool for every fragment
// that passes the depth test (or every covered fragment with depth_test off) before it
// is written.
// Concurrency contract of `test`: it is called from several threads at once, but never
// for two fragments of the same pixel at once; for one pixel the calls come in draw order
// (the order of `objects` / `triangles` / the scene). A test that keeps per-pixel state
// in its own image is therefore race-free and deterministic.
// A test may also have keep_run(const Fragment*, int n) → uint64_t (bit k keeps fragment
// k): with the depth test on, the rasterizer calls it instead, once per row run of a
// triangle with the run's depth-passing fragments (raster_frame.h, RunFragmentTest) —
// the same fragments in the same per-pixel order, so it must answer as the per-fragment
// test would. And it may have keeps_all(uint32_t triangle) → bool: where true, it would
// keep every fragment of that triangle, and the rasterizer keeps them without calling it.
// And it may have prefetch(uint32_t triangle): a hint that the rasterizer will soon test
// that triangle's fragments (fetch per-triangle data); it must not change any answer.
// Throws InputError for an invalid camera (validate_camera).
template <typename FragmentTest>
RasterStats rasterize(const Scene& scene, const Camera& camera, const RasterOptions& options,
                      RasterImages& out, FragmentTest&& test);

// Rasterizes with every fragment kept. Returns the images requested in options.outputs.
RasterImages rasterize(const Scene& scene, const Camera& camera, const RasterOptions& options = {},
                       RasterStats* stats = nullptr);

}  // namespace proxima

#include "proxima/raster/detail/raster_frame.h"  // the template above, and its tile loop
