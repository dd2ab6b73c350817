// The GIBR study on tiny photographs and views of the rooms model: novel views close to the
// ground truth, every photograph's map passing its self-check, determinism across thread
// counts, the view sets, camera-file photographs, and the options' errors naming their flags.
#include "proxima/study/gibr.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "../test_util.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/load.h"
#include "study_test_util.h"

namespace proxima::study {
namespace {

GibrOptions tiny() {
  GibrOptions o;
  o.model.photos = 8;
  o.model.photo_width = 64;
  o.model.photo_height = 48;
  o.model.supersample = 1;
  o.width = 64;
  o.height = 48;
  o.frames = 2;
  o.fps_repeat = 1;
  return o;
}

// PSNR floors where both mappings saw the surface: 8 photographs leave much of each view
// unseen, but what was seen must be mapped from the right photograph (docs/gibr.md).
TEST(GibrStudy, NovelViewsMatchTheGroundTruthWhereSeen) {
  const Results r = run_gibr(load_scene("rooms"), tiny(), {});
  const auto& m = r.metrics;
  EXPECT_EQ(m.at("photos"), 8.0);
  EXPECT_EQ(m.at("maps_failed_selfcheck"), 0.0);
  EXPECT_GT(m.at("psnr_seen_vismap"), 20.0);
  EXPECT_GT(m.at("psnr_seen_itembuffer"), 20.0);
  EXPECT_LT(m.at("unseen_pct_vismap"), 100.0);
  EXPECT_GT(m.at("pixels_mapped_vismap"), 0.0);
  EXPECT_EQ(m.at("novel_view_ss"), 1.0);
  EXPECT_FALSE(m.count("novel_view_fps_1spp"));  // no supersampling, no 1-sample comparison
  ASSERT_EQ(r.tables.size(), 5u);
  EXPECT_EQ(r.tables[4].rows.size(), 2u);  // one row per view
  EXPECT_TRUE(r.images.empty());           // nothing written, no roles
}

// At a photograph's own pose the blend takes that photograph (weights ≈ 2/θ²): views at
// the photo poses are far closer to the truth than views along the path.
TEST(GibrStudy, ViewsAtThePhotoPosesReproduceThePhotographs) {
  GibrOptions o = tiny();
  o.views = GibrViews::Photos;
  const Results at_photos = run_gibr(load_scene("rooms"), o, {});
  o.views = GibrViews::Path;
  const Results on_path = run_gibr(load_scene("rooms"), o, {});
  EXPECT_GT(at_photos.metrics.at("psnr_vismap"), 30.0);
  EXPECT_GT(at_photos.metrics.at("psnr_vismap"), on_path.metrics.at("psnr_vismap") + 5.0);
  EXPECT_LT(at_photos.metrics.at("unseen_pct_vismap"), 1.0);
}

TEST(GibrStudy, SameResultsAtOneAndTwoThreads) {
  const Scene scene = load_scene("rooms");
  GibrOptions o = tiny();
  o.model.supersample = 2;
  Results a, b;
  {
    ThreadLimit one(1);
    a = run_gibr(scene, o, {});
  }
  {
    ThreadLimit two(2);
    b = run_gibr(scene, o, {});
  }
  EXPECT_GT(expect_same_metrics(a, b), 25u);
}

// --novel-ss 0 renders the novel views antialiased like the ground truth, and times one
// sample per pixel beside it; off-path views are written with their roles.
TEST(GibrStudy, OffpathViewsAntialiasedLikeTheTruth) {
  TempDir dir;
  GibrOptions o = tiny();
  o.model.supersample = 2;
  o.views = GibrViews::Offpath;
  o.photo_images = false;
  const Results r = run_gibr(load_scene("rooms"), o, {dir.path / "out"});
  EXPECT_EQ(r.metrics.at("novel_view_ss"), 2.0);
  EXPECT_TRUE(r.metrics.count("novel_view_fps_1spp"));
  for (const char* f : {"views/vismap_001.png", "views/error_itembuffer_001.png", "views/unseen_vismap_001.png",
                        "photos/cameras.json"})
    EXPECT_TRUE(std::filesystem::exists(dir.path / "out" / f)) << f;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "out" / "photos" / "photo_000.png"));
  EXPECT_EQ(r.images.at("error_vismap"), "views/error_vismap_000.png");
  EXPECT_EQ(r.images.size(), 5u);
}

// Photographs read from a camera file (a first run's photos/: 8-bit sRGB PNGs of its linear
// renders) give the radiance maps the rendered ones gave, up to that quantization.
TEST(GibrStudy, CameraFilePhotographsMapLikeTheRenderedOnes) {
  TempDir dir;
  const Scene rooms = load_scene("rooms");
  GibrOptions o = tiny();
  o.model.photos = 4;
  const Results a = run_gibr(rooms, o, {dir.path / "rendered"});
  o.model.camera_file = dir.path / "rendered" / "photos" / "cameras.json";
  const Results b = run_gibr(rooms, o, {});
  for (const char* m : {"psnr_seen_vismap", "psnr_seen_itembuffer"}) {
    EXPECT_GT(b.metrics.at(m), 18.0) << m;
    EXPECT_NEAR(b.metrics.at(m), a.metrics.at(m), 0.5) << m;
  }
  EXPECT_EQ(b.metrics.at("unseen_pct_vismap"), a.metrics.at("unseen_pct_vismap"));
  // An image that is not the size its camera says: InputError naming it, nothing written.
  write_file(dir.path / "bad" / "cameras.json",
             R"({"format": "proxima-cameras", "version": 1, "photos": [{"image": "photo_000.png", "width": 32,
                 "height": 24, "vfov_deg": 60, "position": [0, 1.5, 0], "orientation": [1, 0, 0, 0],
                 "near": 0.01, "far": 100}]})");
  std::filesystem::copy_file(dir.path / "rendered" / "photos" / "photo_001.png", dir.path / "bad" / "photo_000.png");
  o.model.camera_file = dir.path / "bad" / "cameras.json";
  const std::string e = error_of([&] { run_gibr(rooms, o, {dir.path / "never"}); });
  EXPECT_NE(e.find("photo_000.png"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "never"));
}

TEST(GibrStudy, ViewSetNamesRoundTripAndUnknownOnesListTheValidNames) {
  for (GibrViews v : {GibrViews::Path, GibrViews::Offpath, GibrViews::Photos})
    EXPECT_EQ(parse_gibr_views(gibr_views_name(v), "--views"), v);
  const std::string e = error_of([] { parse_gibr_views("sideways", "--views"); });
  for (const char* part : {"--views", "sideways", "'path'", "'offpath'", "'photos'"})
    EXPECT_NE(e.find(part), std::string::npos) << part << ": " << e;
}

TEST(GibrStudy, BadOptionsNameTheirFlag) {
  auto error = [](void (*change)(GibrOptions&)) {
    GibrOptions o = tiny();
    change(o);
    return error_of([&] { validate(o); });
  };
  EXPECT_NE(error([](GibrOptions& o) { o.frames = 0; }).find("--frames"), std::string::npos);
  EXPECT_NE(error([](GibrOptions& o) { o.k = 0; }).find("--k"), std::string::npos);
  EXPECT_NE(error([](GibrOptions& o) { o.novel_ss = 9; }).find("--novel-ss"), std::string::npos);
  EXPECT_NE(error([](GibrOptions& o) { o.hole_radius = -1; }).find("--hole-radius"), std::string::npos);
  EXPECT_NE(error([](GibrOptions& o) { o.offpath = -1; }).find("--offpath"), std::string::npos);
  EXPECT_NE(error([](GibrOptions& o) { o.fps_repeat = 0; }).find("--fps-repeat"), std::string::npos);
  EXPECT_NE(error([](GibrOptions& o) { o.width = kMaxImageSide + 1; }).find("--width/--height"), std::string::npos);
  EXPECT_EQ(error([](GibrOptions&) {}), "");
  // The model's options are checked as the run starts, before any work.
  GibrOptions o = tiny();
  o.model.photos = 0;
  EXPECT_NE(error_of([&] { run_gibr(load_scene("rooms"), o, {}); }).find("--photos"), std::string::npos);
}

}  // namespace
}  // namespace proxima::study
