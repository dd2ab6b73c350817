// Sheared views (one orientation, eyes translated in the image plane): the shared vertex
// transform against each view's own transform, and each view against a centred camera at
// its eye.
#include "proxima/raster/sheared_depth_raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/parallel.h"
#include "clutter_scene.h"

namespace proxima {
namespace {

using raster_test::clutter;

// Eyes on a 3×3 grid in the plane y = 4, 0.6 m apart, looking down (−y), images of
// 180 × 150 texels whose principal points move with the eye; pixel scale `to_pixel`.
ShearedViews grid_views(glm::mat2 to_pixel) {
  ShearedViews v;
  v.origin = vec3(0.1f, 4.0f, -0.2f);
  v.orientation = look_at(v.origin, v.origin - vec3(0, 1, 0), vec3(0, 0, -1), 90.0f, 16, 16).orientation;
  v.to_pixel = to_pixel;
  v.near = 0.1f;
  v.far = 20.0f;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      ShearedView view;
      view.offset = vec2(0.6f * float(i), 0.6f * float(j));
      view.principal = vec2(90.0f + 13.25f * float(i), 75.0f - 7.5f * float(j));
      view.width = 180;
      view.height = 150;
      v.views.push_back(view);
    }
  return v;
}

// Texels where a and b disagree: covered in one only, or depths apart by more than a
// relative 1e-5 (float rounding of the same plane).
double disagreeing_fraction(const ImageF& a, const ImageF& b) {
  size_t differ = 0;
  for (size_t i = 0; i < a.data().size(); ++i) {
    const float x = a.data()[i], y = b.data()[i];
    if (std::isinf(x) != std::isinf(y) || (!std::isinf(x) && std::abs(x - y) > 1e-5f * std::abs(y))) ++differ;
  }
  return double(differ) / double(a.data().size());
}

// The shared transform (double, shifted per view) snaps a vertex where the view's own float
// transform does, but for that transform's rounding: |X| ≲ (f·|c.x| + principal·W) is
// rounded to 2^−24 relative, a few 1/4096 texel at these sizes, which moves an edge across
// a texel centre only for the few centres that close to an edge.
TEST(ShearedDepthRaster, SharedTransformAgreesWithEachViewsOwnTransform) {
  const Scene scene = clutter();
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  // Scaled, flipped and skewed, as the shadow maps' grids are.
  const ShearedViews views = grid_views(glm::mat2(70.0f, 12.0f, -9.0f, -85.0f));
  const ShearedDepthRaster shared(scene, views, bounds);
  DepthRasterScratch scratch;
  ImageF a, b;
  double worst = 0.0;
  for (size_t k = 0; k < views.views.size(); ++k) {
    const RasterStats sa = shared.draw(k, CullMode::None, a, scratch);
    const RasterStats sb = rasterize_sheared_view(scene, views, k, bounds, CullMode::None, b, scratch);
    ASSERT_EQ(a.width(), 180);
    ASSERT_EQ(b.height(), 150);
    worst = std::max(worst, disagreeing_fraction(a, b));
    EXPECT_EQ(sa.triangles_submitted, sb.triangles_submitted);
    EXPECT_NEAR(double(sa.triangles_rasterized), double(sb.triangles_rasterized), 1e-3 * double(sb.triangles_rasterized));
    EXPECT_GT(sa.triangles_rasterized, 5000u);
  }
  EXPECT_LT(worst, 1e-3);
}

// View k is the image of a centred camera at its eye with the same orientation, shifted by
// a whole number of texels: a view drawn with the wrong shift (sign, axis or scale) lands
// elsewhere and disagrees on most covered texels.
TEST(ShearedDepthRaster, ViewIsTheCentredCameraAtItsEyeCropped) {
  const Scene scene = clutter();
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  // A 400² centred camera; its focal length as the rasterizer reads it.
  Camera centred;
  centred.width = centred.height = 400;
  centred.vfov_deg = 2.0f * glm::degrees(std::atan(200.0f / 80.0f));
  centred.near = 0.1f;
  centred.far = 20.0f;
  const float f = focal_length_px(centred);
  ShearedViews views = grid_views(glm::mat2(f, 0.0f, 0.0f, -f));
  // View k's texel (x, y) is the centred camera's texel (x + ox, y + oy).
  const int ox = 117, oy = 131;
  for (ShearedView& v : views.views) v.principal = vec2(200.0f - float(ox), 200.0f - float(oy));
  const ShearedDepthRaster shared(scene, views, bounds);
  DepthRasterScratch scratch;
  ImageF view_depth, full;
  for (size_t k = 0; k < views.views.size(); ++k) {
    shared.draw(k, CullMode::None, view_depth, scratch);
    centred.position = sheared_eye(views, k);
    centred.orientation = views.orientation;
    rasterize_depth_serial(scene, centred, bounds, CullMode::None, full, scratch);
    ImageF crop(view_depth.width(), view_depth.height(), 1, 0.0f);
    size_t covered = 0;
    for (int y = 0; y < crop.height(); ++y)
      for (int x = 0; x < crop.width(); ++x) {
        crop.at(x, y) = full.at(x + ox, y + oy);
        covered += !std::isinf(view_depth.at(x, y));
      }
    EXPECT_GT(covered, size_t(crop.width() * crop.height() / 2)) << k;
    EXPECT_LT(disagreeing_fraction(view_depth, crop), 1e-3) << k;
    // The receivers' projection agrees with the centred camera's.
    const vec3 p(0.3f, -0.8f, 0.4f);
    const auto q = sheared_project(views, k, p), r = project(centred, p);
    ASSERT_TRUE(q && r);
    EXPECT_NEAR(q->pixel.x, r->pixel.x - float(ox), 1e-3f);
    EXPECT_NEAR(q->pixel.y, r->pixel.y - float(oy), 1e-3f);
    EXPECT_NEAR(q->depth, r->depth, 1e-5f);
  }
}

// The views are independent and each is drawn by one thread: the same images for any
// thread count and order.
TEST(ShearedDepthRaster, SameImagesForAnyThreadCount) {
  const Scene scene = clutter();
  const ShearedViews views = grid_views(glm::mat2(60.0f, 0.0f, 5.0f, -55.0f));
  std::vector<ImageF> one(views.views.size()), two(views.views.size());
  for (auto* images : {&one, &two}) {
    ThreadLimit limit(images == &one ? 1 : 2);
    const ShearedDepthRaster shared(scene, views, {});
    parallel_for(views.views.size(), 1, [&](size_t k0, size_t k1) {
      DepthRasterScratch scratch;
      for (size_t k = k1; k-- > k0;) shared.draw(k, CullMode::None, (*images)[k], scratch);
    });
  }
  for (size_t k = 0; k < one.size(); ++k) EXPECT_TRUE(one[k] == two[k]) << k;
}

}  // namespace
}  // namespace proxima
