// Conventional sampling, depth peeling and NRR on the thesis' Figure 11 scene and on a
// cluttered scene: what each captures, image 0 equality, the superset property, thread
// independence.
#include "proxima/depthimage/sampling.h"

#include <gtest/gtest.h>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "figure11.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/builtin_scenes.h"

namespace proxima {
namespace {

// Pixels of `image` holding a triangle of object `object`.
size_t object_pixels(const Scene& scene, const DepthImage& image, uint32_t object) {
  size_t n = 0;
  for (uint32_t t : image.triangle.data()) n += t != kNoTriangle && scene.triangle_object[t] == object;
  return n;
}

std::string param_name(const testing::TestParamInfo<Redundancy>& p) { return redundancy_name(p.param); }

std::vector<Camera> corners(const ViewSet& set) {
  std::vector<Camera> c;
  for (size_t i = 0; i < set.corners.size(); ++i) c.push_back(corner_camera(set, i));
  return c;
}

class Figure11 : public testing::TestWithParam<Redundancy> {};

TEST_P(Figure11, NrrCapturesCWhichConventionalAndTwoLayerPeelingMiss) {
  const Scene scene = figure11::scene();
  const RayScene rays(scene);
  const std::vector<Camera> cams = corners(figure11::views(200));
  const auto conventional = sample_conventional(scene, cams, false);
  const auto nrr = sample_nrr(scene, cams, GetParam(), &rays, false);
  const auto peeled = sample_peeling(scene, cams[0], 2, false);  // Figure 11 (right): from V_0

  for (const DepthImage& image : conventional) EXPECT_EQ(object_pixels(scene, image, figure11::kC), 0u);
  for (const DepthImage& image : peeled) EXPECT_EQ(object_pixels(scene, image, figure11::kC), 0u);
  EXPECT_EQ(object_pixels(scene, nrr[0], figure11::kC), 0u);
  EXPECT_GT(object_pixels(scene, nrr[1], figure11::kC), 200u);
  // I_0 holds A and D; B hides behind A from V_0, so I_1 holds it (NRR and conventional).
  EXPECT_GT(object_pixels(scene, nrr[0], figure11::kA), 0u);
  EXPECT_GT(object_pixels(scene, nrr[0], figure11::kD), 0u);
  EXPECT_EQ(object_pixels(scene, nrr[0], figure11::kB), 0u);
  EXPECT_GT(object_pixels(scene, nrr[1], figure11::kB), 0u);
  EXPECT_GT(object_pixels(scene, conventional[1], figure11::kB), 0u);
  // A third peeled layer does reach C.
  const auto three = sample_peeling(scene, cams[0], 3, false);
  EXPECT_GT(object_pixels(scene, three[2], figure11::kC), 0u);
}

INSTANTIATE_TEST_SUITE_P(Nrr, Figure11, testing::Values(Redundancy::Pixel, Redundancy::Visibility),
                         param_name);

// A cluttered scene where redundancy and occlusion are everywhere (box canyons).
Scene clutter() { return make_builtin_scene("city"); }

ViewSet clutter_views(const Scene& scene, int size) {
  Camera base = scene.cameras[0].camera;
  base.width = base.height = size;
  return make_view_set(ViewShape::Triangle, base, 5.0f, 60.0f);
}

class NrrOnClutter : public testing::TestWithParam<Redundancy> {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(clutter());
    rays_ = new RayScene(*scene_);
  }
  static void TearDownTestSuite() {
    delete rays_;
    delete scene_;
  }
  static Scene* scene_;
  static RayScene* rays_;
};
Scene* NrrOnClutter::scene_ = nullptr;
RayScene* NrrOnClutter::rays_ = nullptr;

TEST_P(NrrOnClutter, ImageZeroEqualsConventionalImageZero) {
  const std::vector<Camera> cams = corners(clutter_views(*scene_, 96));
  const auto conventional = sample_conventional(*scene_, cams, true);
  const auto nrr = sample_nrr(*scene_, cams, GetParam(), rays_, true);
  EXPECT_EQ(nrr[0].triangle, conventional[0].triangle);
  EXPECT_EQ(nrr[0].depth, conventional[0].depth);
  EXPECT_EQ(nrr[0].color, conventional[0].color);
  EXPECT_NE(nrr[1].triangle, conventional[1].triangle);  // it did discard something
}

// Wherever conventional image i holds a sample that is non-redundant with NRR images < i,
// that sample is the nearest non-redundant fragment, so NRR image i holds it too.
TEST_P(NrrOnClutter, SupersetOfConventionalNonRedundantSamples) {
  const std::vector<Camera> cams = corners(clutter_views(*scene_, 96));
  const auto conventional = sample_conventional(*scene_, cams, false);
  const auto nrr = sample_nrr(*scene_, cams, GetParam(), rays_, false);
  size_t checked = 0;
  for (size_t i = 1; i < cams.size(); ++i) {
    std::vector<RedundancyTest> earlier;
    for (size_t j = 0; j < i; ++j) earlier.emplace_back(GetParam(), *scene_, rays_, cams[i], nrr[j]);
    const DepthImage& c = conventional[i];
    for (int y = 0; y < c.triangle.height(); ++y) {
      for (int x = 0; x < c.triangle.width(); ++x) {
        const uint32_t t = c.triangle.at(x, y);
        if (t == kNoTriangle) continue;
        bool redundant = false;
        for (const RedundancyTest& r : earlier) redundant = redundant || r(x, y, c.depth.at(x, y), t);
        if (redundant) continue;
        ++checked;
        ASSERT_EQ(nrr[i].triangle.at(x, y), t) << "image " << i << " pixel " << x << "," << y;
      }
    }
  }
  EXPECT_GT(checked, 1000u);
}

TEST_P(NrrOnClutter, SameImagesForOneAndTwoThreads) {
  const std::vector<Camera> cams = corners(clutter_views(*scene_, 80));
  std::vector<DepthImage> one, two;
  {
    ThreadLimit limit(1);
    one = sample_nrr(*scene_, cams, GetParam(), rays_, true);
  }
  {
    ThreadLimit limit(2);
    two = sample_nrr(*scene_, cams, GetParam(), rays_, true);
  }
  for (size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].triangle, two[i].triangle);
    EXPECT_EQ(one[i].depth, two[i].depth);
    EXPECT_EQ(one[i].color, two[i].color);
  }
}

// sample_nrr takes shortcuts (front-to-back draw order, a per-triangle presence mask
// for pixel redundancy); they must not change a bit of the output. Reference: Algorithm
// 1 written out directly — scene order, every earlier image tested for every fragment.
std::vector<DepthImage> reference_nrr(const Scene& scene, std::span<const Camera> cams, Redundancy kind,
                                      const RayScene* rays) {
  std::vector<DepthImage> images;
  images.reserve(cams.size());
  for (size_t i = 0; i < cams.size(); ++i) {
    std::vector<RedundancyTest> earlier;
    for (size_t j = 0; j < i; ++j) earlier.emplace_back(kind, scene, rays, cams[i], images[j]);
    RasterImages out;
    rasterize(scene, cams[i], depth_image_raster_options(true), out, [&](const Fragment& f) {
      for (const RedundancyTest& r : earlier)
        if (r(f.x, f.y, f.depth, f.triangle)) return false;
      return true;
    });
    images.push_back(to_depth_image(cams[i], std::move(out)));
  }
  return images;
}

// All four scenes for pixel redundancy (its run form reprojects four fragments at once);
// the costlier visibility test on two.
TEST_P(NrrOnClutter, SameImagesAsAlgorithmOneWrittenOut) {
  const bool pixel = GetParam() == Redundancy::Pixel;
  for (const char* name : {"city", "nest", "grass", "tree"}) {
    if (!pixel && (std::string(name) == "grass" || std::string(name) == "tree")) continue;
    const Scene scene = make_builtin_scene(name);
    const std::optional<RayScene> rays = pixel ? std::nullopt : std::optional<RayScene>(std::in_place, scene);
    Camera base = scene.cameras[0].camera;
    base.width = base.height = 120;
    const float focus = glm::length(scene_bounds(scene).center() - base.position);
    const std::vector<Camera> cams = corners(make_view_set(ViewShape::Triangle, base, 0.08f * focus, focus));
    const RayScene* ray_ptr = rays ? &*rays : nullptr;
    const auto fast = sample_nrr(scene, cams, GetParam(), ray_ptr, true);
    const auto reference = reference_nrr(scene, cams, GetParam(), ray_ptr);
    for (size_t i = 0; i < cams.size(); ++i) {
      EXPECT_EQ(fast[i].triangle, reference[i].triangle) << name << " image " << i;
      EXPECT_EQ(fast[i].depth, reference[i].depth) << name << " image " << i;
      EXPECT_EQ(fast[i].color, reference[i].color) << name << " image " << i;
      EXPECT_EQ(fast[i].normal, reference[i].normal) << name << " image " << i;
    }
    EXPECT_GT(sample_count(fast[1]), 0u);
  }
}

// The pixel shortcut reprojects a fragment only into the earlier images that hold its
// triangle, one mask bit per image and images 7, 8, … sharing the last bit: twelve views
// (three rectangles) cover images past that bit.
TEST_P(NrrOnClutter, SameImagesAsAlgorithmOneWrittenOutWithTwelveViews) {
  Camera base = scene_->cameras[0].camera;
  base.width = base.height = 48;
  std::vector<Camera> cams;
  for (float radius : {2.0f, 4.0f, 6.0f})
    for (const Camera& c : corners(make_view_set(ViewShape::Rectangle, base, radius, 60.0f))) cams.push_back(c);
  ASSERT_EQ(cams.size(), 12u);
  const auto fast = sample_nrr(*scene_, cams, GetParam(), rays_, false);
  const auto reference = reference_nrr(*scene_, cams, GetParam(), rays_);
  size_t late = 0;
  for (size_t i = 0; i < cams.size(); ++i) {
    EXPECT_EQ(fast[i].triangle, reference[i].triangle) << "image " << i;
    EXPECT_EQ(fast[i].depth, reference[i].depth) << "image " << i;
    if (i >= 8) late += sample_count(fast[i]);
  }
  EXPECT_GT(late, 0u);  // images past the shared bit keep samples: the test is not vacuous
}

INSTANTIATE_TEST_SUITE_P(Nrr, NrrOnClutter, testing::Values(Redundancy::Pixel, Redundancy::Visibility),
                         param_name);

TEST(SamplingPeeling, AlwaysReturnsTheRequestedLayerCount) {
  const Scene scene = figure11::scene();
  const auto layers = sample_peeling(scene, corner_camera(figure11::views(64), 0), 9, false);
  ASSERT_EQ(layers.size(), 9u);
  EXPECT_EQ(sample_count(layers[8]), 0u);  // the scene has fewer front faces per pixel
  EXPECT_GT(sample_count(layers[0]), 0u);
}

}  // namespace
}  // namespace proxima
