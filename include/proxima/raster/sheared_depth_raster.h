// Depth images of a family of pinhole views that share one orientation and one image plane
// and differ by a translation of the eye within that plane — the samples of a planar area
// light. View k sees world point p at
//   c = R⁻¹ (p − origin),   W = −c.z   (the same for every view)
//   (x, y) = A · ((c.x, c.y) − offset_k) / W + principal_k
// (continuous pixel coordinates of its width_k × height_k image, depth W; A = to_pixel, a
// 2×2 map from the image plane to pixels that may scale, flip and skew): an off-centre
// (sheared) projection of the eye origin + R·(offset_k, 0). Since W does not depend on k,
// a vertex is transformed once — (x', y') = A·(c.x, c.y)/W and g = 1/W — and each view's
// position is (x', y') − g·A·offset_k + principal_k: two multiply-adds per coordinate
// instead of a transform and two divisions per view. A centred pinhole camera of focal f
// at the eye with orientation R is A = diag(f, −f) with the principal point at its centre.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/raster/depth_raster.h"

namespace proxima {

struct ShearedView {
  vec2 offset{0.0f};     // eye − origin along the shared camera's x and y
  vec2 principal{0.0f};  // pixel position of the shared axis seen from this eye
  int width = 1, height = 1;
};

struct ShearedViews {
  vec3 origin{0.0f};
  quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // camera → world, as Camera::orientation
  glm::mat2 to_pixel{1.0f};  // A above (glm column-major: to_pixel * t)
  float near = 0.01f, far = 1000.0f;
  std::vector<ShearedView> views;
};

// Eye of view k in world space.
vec3 sheared_eye(const ShearedViews& v, size_t k);

// World point → view k's pixel coordinates and depth W; nullopt when W ≤ 0. The pixel may
// lie outside the image.
std::optional<Projection> sheared_project(const ShearedViews& v, size_t k, vec3 world);

// View k as rasterize_depth_serial (depth_raster.h) draws a Camera: its own world → clip
// transform in float, the same clipping, snapping, coverage and depth. The reference the
// shared transform below is checked against.
RasterStats rasterize_sheared_view(const Scene& scene, const ShearedViews& v, size_t k,
                                   std::span<const Bounds3> bounds, CullMode cull, ImageF& depth,
                                   DepthRasterScratch& scratch);

// Every vertex of `scene` transformed once for all views (double precision), then any view
// drawn from it: per view only the shift, the 20.12 snap and the triangles' coverage. The
// near and far planes are shared; the guard band and the image sides are per view. A
// triangle that needs clipping in a view goes through that view's own transform and the
// clipper, as rasterize_sheared_view does. Depth as rasterize_depth_serial (−z along the
// shared axis, +inf where empty); it differs from rasterize_sheared_view's only where a
// snapped vertex differs by the float rounding of that path's transform (a few 1/4096 px).
// draw() may run concurrently for different views with one scratch each.
class ShearedDepthRaster {
 public:
  ShearedDepthRaster(const Scene& scene, const ShearedViews& views, std::span<const Bounds3> bounds);
  RasterStats draw(size_t k, CullMode cull, ImageF& depth, DepthRasterScratch& scratch) const;
  // The same image as 1/W, row-major, 0 where empty, in a buffer the caller reuses across
  // views (no allocation once it is large enough).
  // With `needed` (its size view k's), triangles are culled as rasterize_depth_serial's
  // overload with a texel mask culls them.
  RasterStats draw_inverse(size_t k, CullMode cull, std::vector<float>& inv_depth, DepthRasterScratch& scratch,
                           const TexelMask* needed = nullptr) const;

  struct Vertex {
    double x, y, g;  // A·(c.x, c.y)/W and 1/W
    float W, iw;    // W and 1.0f / W in float, as the per-view path has them
    uint32_t code;  // the bits every view shares: near, far, not finite
  };

 private:
  const Scene& scene_;
  const ShearedViews& views_;
  std::span<const Bounds3> bounds_;
  std::vector<Vertex> vertices_;
};

}  // namespace proxima
