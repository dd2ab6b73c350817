// `proxima gibr`: a tiny run writes the metrics the issue names; bad flags exit 2 naming the
// flag and write nothing.
#include <gtest/gtest.h>

#include <filesystem>

#include "../cli/cli_util.h"
#include "proxima/eval/results.h"

namespace proxima {
namespace {

TEST(GibrCli, TinyRunWritesTheComparisonMetrics) {
  TempDir dir;
  const auto out = dir.path / "gibr";
  RunResult r = run_cli("gibr --scene rooms --photos 4 --frames 2 --width 64 --height 48 --photo-width 64 "
                        "--photo-height 48 --supersample 1 --threads 2 --no-photo-images --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Results res = read_results_json(out / "results.json");
  for (const char* m : {"psnr_vismap", "psnr_itembuffer", "silhouette_mae_vismap", "silhouette_mae_itembuffer",
                        "novel_view_fps"}) {
    ASSERT_TRUE(res.metrics.count(m)) << m;
    EXPECT_GT(res.metrics.at(m), 0.0) << m;
  }
  EXPECT_TRUE(std::filesystem::exists(out / "photos" / "cameras.json"));
  EXPECT_TRUE(std::filesystem::exists(out / "views" / "truth_001.png"));
}

TEST(GibrCli, OffpathViewsAntialiasedLikeTheTruthWithNovelSsZero) {
  TempDir dir;
  const auto out = dir.path / "gibr";
  RunResult r = run_cli("gibr --scene rooms --photos 4 --frames 2 --width 32 --height 24 --photo-width 32 "
                        "--photo-height 24 --supersample 2 --views offpath --fps-repeat 1 --threads 2 "
                        "--novel-ss 0 --no-photo-images --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Results res = read_results_json(out / "results.json");
  ASSERT_TRUE(res.metrics.count("novel_view_ss"));
  EXPECT_EQ(res.metrics.at("novel_view_ss"), 2.0);
  EXPECT_TRUE(res.metrics.count("novel_view_fps_1spp"));
  EXPECT_TRUE(std::filesystem::exists(out / "views" / "vismap_001.png"));
}

TEST(GibrCli, BadFlagsExitTwoNamingTheFlagAndWriteNothing) {
  TempDir dir;
  const auto out = dir.path / "never";
  for (const char* args : {"--photos 0", "--views sideways", "--texel -1", "--texel 1e-6", "--k 0", "--supersample 9",
                           "--frames 0", "--novel-ss 9", "--hole-radius -1", "--offpath -1", "--scene no-such-scene", "--photo-width 0", "--threads -1"}) {
    RunResult r = run_cli(std::string("gibr ") + args + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    const std::string flag = std::string(args).substr(0, std::string(args).find(' '));
    if (flag != "--scene") {
      EXPECT_NE(r.output.find(flag), std::string::npos) << args << ": " << r.output;
    }
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
}

// Photographs from a camera file (here a first run's photos/, 8-bit sRGB PNGs of its linear
// renders) give the radiance maps the rendered ones gave, up to that quantization.
TEST(GibrCli, CameraFilePhotographsMapLikeTheRenderedOnes) {
  TempDir dir;
  const std::string common = "gibr --scene rooms --photos 4 --frames 2 --width 64 --height 48 --photo-width 64 "
                             "--photo-height 48 --supersample 1 --novel-ss 1 --fps-repeat 1 --threads 2 --out ";
  RunResult first = run_cli(common + (dir.path / "rendered").string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto cameras = dir.path / "rendered" / "photos" / "cameras.json";
  RunResult second = run_cli(common + (dir.path / "loaded").string() + " --camera-file " + cameras.string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const Results a = read_results_json(dir.path / "rendered" / "results.json");
  const Results b = read_results_json(dir.path / "loaded" / "results.json");
  // 4 photographs leave most of the views unseen: compare where both mappings saw.
  for (const char* m : {"psnr_seen_vismap", "psnr_seen_itembuffer"}) {
    ASSERT_TRUE(a.metrics.count(m) && b.metrics.count(m)) << m;
    EXPECT_GT(b.metrics.at(m), 18.0) << m;
    EXPECT_NEAR(b.metrics.at(m), a.metrics.at(m), 0.5) << m;
  }
  EXPECT_EQ(b.metrics.at("unseen_pct_vismap"), a.metrics.at("unseen_pct_vismap"));
  // A camera file whose image is not the size its camera says: exit 2 naming the image.
  std::filesystem::create_directories(dir.path / "bad");
  std::filesystem::copy_file(dir.path / "rendered" / "photos" / "photo_001.png", dir.path / "bad" / "photo_000.png");
  write_file(dir.path / "bad" / "cameras.json",
             R"({"format": "proxima-cameras", "version": 1, "photos": [{"image": "photo_000.png", "width": 32,
                 "height": 24, "vfov_deg": 60, "position": [0, 1.5, 0], "orientation": [1, 0, 0, 0],
                 "near": 0.01, "far": 100}]})");
  const auto never = dir.path / "never";
  RunResult bad = run_cli(common + never.string() + " --camera-file " + (dir.path / "bad" / "cameras.json").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("photo_000.png"), std::string::npos) << bad.output;
  RunResult missing = run_cli(common + never.string() + " --camera-file " + (dir.path / "nope.json").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("nope.json"), std::string::npos) << missing.output;
  EXPECT_FALSE(std::filesystem::exists(never));
}

}  // namespace
}  // namespace proxima
