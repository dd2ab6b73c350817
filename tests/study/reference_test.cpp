// study/reference.h: the reference render as a library call — its buffers and metrics, the
// same bits for any thread count, the options' messages naming the flags.
#include "proxima/study/reference.h"

#include <gtest/gtest.h>

#include <cmath>

#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/builtin_scenes.h"
#include "test_util.h"

namespace proxima {
namespace {

study::ReferenceStudyOptions tiny() {
  study::ReferenceStudyOptions o;
  o.width = 48;
  o.height = 32;
  o.supersample = 2;
  o.glossy_rays = 4;
  o.seed = 9;
  return o;
}

TEST(ReferenceStudy, SameBitsForOneAndTwoThreadsOnEveryBuiltinScene) {
  for (const BuiltinSceneInfo& info : builtin_scenes()) {
    const Scene scene = make_builtin_scene(info.name);
    study::ReferenceRender a, b;
    {
      ThreadLimit limit(1);
      a = study::render_reference_view(scene, tiny(), true);
    }
    {
      ThreadLimit limit(2);
      b = study::render_reference_view(scene, tiny(), true);
    }
    EXPECT_TRUE(a.color == b.color) << info.name;
    EXPECT_TRUE(a.item.depth == b.item.depth) << info.name;
    EXPECT_TRUE(a.item.triangle == b.item.triangle) << info.name;
    EXPECT_EQ(a.color.width(), 48);
    EXPECT_EQ(a.color.height(), 32);
    EXPECT_EQ(a.triangles, scene.triangles.size());
  }
}

TEST(ReferenceStudy, ResultsCarryTheCoverageTableAndImages) {
  const Scene scene = make_builtin_scene("cornell");
  TempDir dir;
  const Results r = study::run_reference(scene, tiny(), {dir.path});
  EXPECT_GT(r.metrics.at("render_ms"), 0.0);
  ASSERT_EQ(r.tables.size(), 1u);
  EXPECT_EQ(r.tables[0].title, "render cornell");
  EXPECT_EQ(std::get<double>(r.tables[0].rows[0][3]), 4.0);  // spp: 2×2
  for (const char* role : {"color", "color_linear", "depth", "normal", "triangle_id"}) {
    ASSERT_TRUE(r.images.count(role)) << role;
    EXPECT_TRUE(std::filesystem::exists(dir.path / r.images.at(role))) << role;
  }
  // The EXR colour is the render itself; the coverage is the share of pixels with an id
  // (−1 where nothing was hit) and of finite depth.
  const study::ReferenceRender direct = study::render_reference_view(scene, tiny(), true);
  EXPECT_TRUE(read_exr(dir.path / "color.exr") == direct.color);
  const ImageF ids = read_exr(dir.path / "id.exr");
  const ImageF depth = read_exr(dir.path / "depth.exr");
  size_t with_id = 0;
  for (size_t i = 0; i < ids.data().size(); ++i) {
    with_id += ids.data()[i] >= 0.0f;
    EXPECT_EQ(ids.data()[i] >= 0.0f, std::isfinite(depth.data()[i])) << i;
  }
  EXPECT_GT(with_id, ids.data().size() / 2);  // the box fills most of the view
  EXPECT_DOUBLE_EQ(r.metrics.at("coverage_pct"), 100.0 * double(with_id) / double(ids.data().size()));

  // Without a directory nothing is written and no image roles are listed.
  const Results quiet = study::run_reference(scene, tiny(), {});
  EXPECT_TRUE(quiet.images.empty());
  EXPECT_EQ(quiet.metrics.at("coverage_pct"), r.metrics.at("coverage_pct"));
}

TEST(ReferenceStudy, CoverageCountsMisses) {
  // The cornell box seen from far outside: most primary rays miss it.
  Scene scene = make_builtin_scene("cornell");
  study::ReferenceStudyOptions o = tiny();
  o.bounces = 0;
  scene.cameras.front().camera.position += 40.0f * -camera_forward(scene.cameras.front().camera);
  const Results r = study::run_reference(scene, o, {});
  EXPECT_GT(r.metrics.at("coverage_pct"), 0.0);
  EXPECT_LT(r.metrics.at("coverage_pct"), 50.0);
}

TEST(ReferenceStudy, ValidateNamesTheFlag) {
  const std::pair<void (*)(study::ReferenceStudyOptions&), const char*> cases[] = {
      {[](study::ReferenceStudyOptions& o) { o.supersample = 0; }, "--spp: must be in 1..64"},
      {[](study::ReferenceStudyOptions& o) { o.light_samples = 65; }, "--light-samples: must be in 1..64"},
      {[](study::ReferenceStudyOptions& o) { o.glossy_rays = 0; }, "--glossy-rays: must be in 1..4096"},
      {[](study::ReferenceStudyOptions& o) { o.bounces = 17; }, "--bounces: must be in 0..16"},
  };
  for (const auto& [change, message] : cases) {
    study::ReferenceStudyOptions o;
    EXPECT_EQ(error_of([&] { study::validate(o); }), "");
    change(o);
    EXPECT_EQ(error_of([&] { study::validate(o); }), message);
  }
  const Scene scene = make_builtin_scene("cornell");
  study::ReferenceStudyOptions o = tiny();
  o.camera.camera = "99";
  EXPECT_NE(error_of([&] { study::run_reference(scene, o, {}); }).find("--camera"), std::string::npos);
}

}  // namespace
}  // namespace proxima
