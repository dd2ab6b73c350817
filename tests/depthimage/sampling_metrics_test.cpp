// The four metrics on the Figure 11 scene and a cluttered scene: NRR has no redundant
// samples under its own definition, conventional images have no occluded ones, C is
// occluded and useful, useful ⊆ occluded; on Figure 11 NRR makes more of the output
// frames available.
#include "proxima/depthimage/sampling_metrics.h"

#include <gtest/gtest.h>

#include <vector>

#include "figure11.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/builtin_scenes.h"

namespace proxima {
namespace {

std::string param_name(const testing::TestParamInfo<Redundancy>& p) { return redundancy_name(p.param); }

std::vector<Camera> corners(const ViewSet& set) {
  std::vector<Camera> c;
  for (size_t i = 0; i < set.corners.size(); ++i) c.push_back(corner_camera(set, i));
  return c;
}

class SamplingMetricsOf : public testing::TestWithParam<Redundancy> {};

TEST_P(SamplingMetricsOf, Figure11NrrCapturesUsefulOccludedSamples) {
  const Scene scene = figure11::scene();
  const RayScene rays(scene);
  const ViewSet set = figure11::views(128);
  const std::vector<Camera> cams = corners(set);
  const std::vector<std::vector<DepthImage>> sets = {sample_conventional(scene, cams, false),
                                                     sample_nrr(scene, cams, GetParam(), &rays, false)};
  MetricsOptions options;
  options.redundancy = GetParam();
  options.frames = 24;
  SampleClasses classes;
  const auto m = measure_sampling(scene, rays, set, sets, sets[0], options, &classes);
  ASSERT_EQ(m.size(), 2u);
  const SamplingMetrics &conv = m[0], &nrr = m[1];
  EXPECT_EQ(conv.redundant[0], 0u);
  EXPECT_GT(conv.redundant_pct[1], 50.0);  // V_1 sees mostly what V_0 saw
  EXPECT_EQ(conv.occluded[0] + conv.occluded[1], 0u);
  EXPECT_EQ(nrr.redundant[0] + nrr.redundant[1], 0u);
  EXPECT_EQ(nrr.occluded[0], 0u);
  EXPECT_GT(nrr.occluded[1], 50u);  // C (and D behind A, which V_0 sees elsewhere)
  EXPECT_GT(nrr.useful[1], 0u);      // C is seen from the middle of the segment
  EXPECT_LE(nrr.useful[1], nrr.occluded[1]);
  EXPECT_GE(nrr.available_avg_pct, conv.available_avg_pct);
  EXPECT_LE(nrr.available_min_pct, nrr.available_avg_pct);
  // Every occluded pixel of C's object is classified, and only occluded pixels are.
  size_t classified = 0;
  for (uint8_t c : classes[1][1].data()) classified += c != 0;
  EXPECT_EQ(classified, nrr.occluded[1]);
}

INSTANTIATE_TEST_SUITE_P(Nrr, SamplingMetricsOf, testing::Values(Redundancy::Pixel, Redundancy::Visibility),
                         param_name);

TEST(SamplingMetrics, ClutterNrrZeroRedundancyAndMoreAvailable) {
  const Scene scene = make_builtin_scene("city");
  const RayScene rays(scene);
  Camera base = scene.cameras[0].camera;
  base.width = base.height = 96;
  const ViewSet set = make_view_set(ViewShape::Triangle, base, 5.0f, 60.0f);
  const std::vector<Camera> cams = corners(set);
  for (Redundancy r : {Redundancy::Pixel, Redundancy::Visibility}) {
    const std::vector<std::vector<DepthImage>> sets = {
        sample_conventional(scene, cams, false), sample_nrr(scene, cams, r, &rays, false),
        sample_peeling(scene, centroid_camera(set), 3, false)};
    MetricsOptions options;
    options.redundancy = r;
    options.frames = 8;
    const auto m = measure_sampling(scene, rays, set, sets, sets[0], options);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(m[1].redundant[i], 0u) << redundancy_name(r) << " " << i;
    EXPECT_GT(m[0].redundant_pct[1], 20.0);
    EXPECT_GT(m[1].occluded_pct[2], m[0].occluded_pct[2]);
    // Not asserted: NRR ≥ conventional availability. It depends on the scene and the
    // resolution (on living-room at 96² the conventional set won: it holds each visible
    // triangle up to three times, and pixel redundancy is not transitive;
    // docs/depthimage.md).
    EXPECT_LE(m[1].available_min_pct, m[1].available_avg_pct);
    if (r == Redundancy::Pixel) {
      // Peeled layers are disjoint per pixel: a later layer never holds a triangle an
      // earlier layer holds at the same pixel.
      EXPECT_EQ(m[2].redundant[1], 0u);
    }
  }
}

TEST(SamplingMetrics, SameFiguresForOneAndTwoThreads) {
  const Scene scene = figure11::scene();
  const RayScene rays(scene);
  const ViewSet set = figure11::views(64);
  const std::vector<Camera> cams = corners(set);
  const std::vector<std::vector<DepthImage>> sets = {sample_nrr(scene, cams, Redundancy::Visibility, &rays, false)};
  MetricsOptions options;
  options.redundancy = Redundancy::Visibility;
  options.frames = 6;
  std::vector<SamplingMetrics> one, two;
  {
    ThreadLimit limit(1);
    one = measure_sampling(scene, rays, set, sets, sets[0], options);
  }
  {
    ThreadLimit limit(2);
    two = measure_sampling(scene, rays, set, sets, sets[0], options);
  }
  EXPECT_EQ(one[0].useful, two[0].useful);
  EXPECT_EQ(one[0].occluded, two[0].occluded);
  EXPECT_EQ(one[0].available_avg_pct, two[0].available_avg_pct);
}

}  // namespace
}  // namespace proxima
