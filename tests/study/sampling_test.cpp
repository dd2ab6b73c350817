// The sampling study (study/sampling.h) on the thesis' Figure 11 scene: NRR under its own
// definition has no redundant samples and makes more of the intermediate frames' samples
// available than conventional images; metric names and prefixes; images only with an
// output directory; the same figures and files for 1 and 2 threads; validation naming the
// flag; the enum names.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "depthimage/figure11.h"
#include "proxima/core/parallel.h"
#include "proxima/study/sampling.h"
#include "study_test_util.h"
#include "test_util.h"

namespace proxima {
namespace {

using study::SamplingMethod;

// Figure 11 seen from the midpoint of V_0 and V_1 (the study's view set: a segment of
// radius 1 around it, as figure11::views).
Scene figure11_scene() {
  Scene s = figure11::scene();
  s.cameras.push_back({"mid", figure11::views(64).base});
  return s;
}

study::SamplingOptions small_options(int size) {
  study::SamplingOptions o;
  o.width = o.height = size;
  o.views = ViewShape::Segment;
  o.radius = 1.0f;
  o.frames = 16;
  o.reps = 1;
  o.methods = {SamplingMethod::Conventional, SamplingMethod::Peeling, SamplingMethod::NrrPixel};
  return o;
}

bool is_timing(const std::string& metric) { return metric.find("_ms") != std::string::npos; }

TEST(SamplingStudy, Figure11NrrHoldsTheOccludedBoxConventionalImagesMiss) {
  const Scene scene = figure11_scene();
  const Results r = study::run_sampling(scene, small_options(64), {});
  // Two conventional views of a wall and slabs hold much the same samples.
  EXPECT_GT(r.metrics.at("conventional_redundant_pct_1"), 20.0);
  EXPECT_EQ(r.metrics.at("nrr_pixel_redundant_pct_1"), 0.0);  // NRR under its own definition
  EXPECT_GT(r.metrics.at("nrr_pixel_occluded_pct_1"), 0.0);    // what A hides from both views (C)
  EXPECT_GT(r.metrics.at("nrr_pixel_useful_pct_1"), 0.0);      // the midpoint frames see part of C
  EXPECT_GT(r.metrics.at("nrr_pixel_available_avg_pct"), r.metrics.at("conventional_available_avg_pct"));
  EXPECT_EQ(r.metrics.at("conventional_occluded_pct_0"), 0.0);  // conventional images hold nothing occluded
  for (const char* p : {"conventional_", "peeling_", "nrr_pixel_"}) {
    const std::string prefix = p;
    EXPECT_LE(r.metrics.at(prefix + "available_min_pct"), r.metrics.at(prefix + "available_avg_pct")) << p;
    EXPECT_TRUE(r.metrics.count(prefix + "time_ms")) << p;
    EXPECT_FALSE(r.metrics.count(prefix + "redundant_pct_2")) << p;  // a segment has two views
  }
  EXPECT_EQ(r.metrics.at("frames"), 16.0);
  EXPECT_EQ(r.metrics.at("triangles"), double(scene.triangles.size()));
  ASSERT_EQ(r.tables.size(), 4u);
  EXPECT_EQ(r.tables[0].rows.size(), 3u);  // one row per method
  EXPECT_EQ(r.tables[2].rows.size(), 6u);  // per method and image
  EXPECT_TRUE(r.images.empty());           // no output directory
}

TEST(SamplingStudy, OneMethodHasNoPrefixAndItsOwnRedundancy) {
  study::SamplingOptions o = small_options(48);
  o.methods = {SamplingMethod::NrrVisibility};
  const Results r = study::run_sampling(figure11_scene(), o, {});
  EXPECT_EQ(r.metrics.at("redundant_pct_1"), 0.0);  // visibility redundancy: NRR's own definition
  EXPECT_FALSE(r.metrics.count("nrr_visibility_redundant_pct_1"));
  EXPECT_NE(r.tables[0].title.find("visibility redundancy"), std::string::npos);
}

TEST(SamplingStudy, WritesEveryImageRoleIntoTheOutputDirectory) {
  TempDir dir;
  study::SamplingOptions o = small_options(32);
  o.methods = {SamplingMethod::NrrPixel};
  const Results r = study::run_sampling(figure11_scene(), o, {dir.path});
  EXPECT_EQ(r.images.size(), 8u);  // 2 images × color, depth, id, occluded
  for (const char* role : {"nrr-pixel_0_color", "nrr-pixel_1_depth", "nrr-pixel_1_id", "nrr-pixel_1_occluded"}) {
    ASSERT_TRUE(r.images.count(role)) << role;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir.path / r.images.at(role))) << role;
  }
  EXPECT_EQ(r.images.at("nrr-pixel_1_depth"), "nrr-pixel_1_depth.exr");
}

TEST(SamplingStudy, SameFiguresAndImagesForOneAndTwoThreads) {
  const Scene scene = figure11_scene();
  study::SamplingOptions o = small_options(48);
  o.methods.push_back(SamplingMethod::NrrVisibility);
  TempDir one_dir, two_dir;
  Results one, two;
  {
    ThreadLimit limit(1);
    one = study::run_sampling(scene, o, {one_dir.path});
  }
  {
    ThreadLimit limit(2);
    two = study::run_sampling(scene, o, {two_dir.path});
  }
  ASSERT_EQ(one.metrics.size(), two.metrics.size());
  for (const auto& [name, value] : one.metrics)
    if (!is_timing(name)) {
      EXPECT_EQ(value, two.metrics.at(name)) << name;
    }
  ASSERT_EQ(one.images, two.images);
  for (const auto& [role, file] : one.images)
    EXPECT_EQ(file_bytes(one_dir.path / file), file_bytes(two_dir.path / file)) << file;
}

TEST(SamplingStudy, ValidateNamesTheFlag) {
  const std::pair<void (*)(study::SamplingOptions&), const char*> cases[] = {
      {[](study::SamplingOptions& o) { o.width = 0; }, "--width"},
      {[](study::SamplingOptions& o) { o.height = kMaxImageSide + 1; }, "--width/--height"},
      {[](study::SamplingOptions& o) { o.frames = -1; }, "--frames"},
      {[](study::SamplingOptions& o) { o.frames = 100001; }, "--frames"},
      {[](study::SamplingOptions& o) { o.reps = 0; }, "--reps"},
      {[](study::SamplingOptions& o) { o.radius = std::nanf(""); }, "--radius"},
      {[](study::SamplingOptions& o) { o.radius = -1.0f; }, "--radius"},
      {[](study::SamplingOptions& o) { o.methods.clear(); }, "--method"},
  };
  for (const auto& [change, flag] : cases) {
    study::SamplingOptions o;
    change(o);
    const std::string error = error_of([&] { study::validate(o); });
    EXPECT_EQ(error.rfind(flag, 0), 0u) << flag << ": " << error;
  }
  EXPECT_EQ(error_of([] { study::validate(study::SamplingOptions{}); }), "");
  study::SamplingOptions o;
  o.camera.camera = "nowhere";
  EXPECT_EQ(error_of([&] { study::validate(o, figure11_scene()); }).rfind("--camera", 0), 0u);
  EXPECT_NE(error_of([&] { study::run_sampling(figure11_scene(), o, {}); }), "");
}

TEST(SamplingStudy, DefaultRedundancyFollowsTheNrrMethods) {
  study::SamplingOptions o;
  o.methods = {SamplingMethod::Conventional, SamplingMethod::NrrVisibility};
  EXPECT_EQ(study::metric_redundancy(o), Redundancy::Visibility);
  o.methods.push_back(SamplingMethod::NrrPixel);
  EXPECT_EQ(study::metric_redundancy(o), Redundancy::Pixel);
  o.redundancy = Redundancy::Visibility;
  EXPECT_EQ(study::metric_redundancy(o), Redundancy::Visibility);
}

TEST(SamplingStudy, EnumNamesRoundTripAndUnknownNamesListTheValidOnes) {
  for (SamplingMethod m : {SamplingMethod::Conventional, SamplingMethod::Peeling, SamplingMethod::NrrPixel,
                           SamplingMethod::NrrVisibility})
    EXPECT_EQ(study::parse_sampling_method(study::sampling_method_name(m), "--method"), m);
  EXPECT_EQ(error_of([] { study::parse_sampling_method("nrr", "--method"); }),
            "--method: unknown method 'nrr' (conventional, peeling, nrr-pixel, nrr-visibility)");
  for (Redundancy r : {Redundancy::Pixel, Redundancy::Visibility})
    EXPECT_EQ(parse_redundancy(redundancy_name(r), "--redundancy"), r);
  EXPECT_EQ(error_of([] { parse_redundancy("strict", "--redundancy"); }),
            "--redundancy: unknown redundancy 'strict' (pixel, visibility)");
}

}  // namespace
}  // namespace proxima
