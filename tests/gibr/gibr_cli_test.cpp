// `proxima gibr` smoke tests (the study's behaviour: tests/study/gibr_test.cpp): a tiny run
// writes the metrics the issue names; bad flags exit 2 naming the flag and write nothing.
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

TEST(GibrCli, BadFlagsExitTwoNamingTheFlagAndWriteNothing) {
  TempDir dir;
  const auto out = dir.path / "never";
  for (const char* args : {"--photos 0", "--views sideways", "--texel -1", "--texel 1e-6", "--k 0", "--supersample 9",
                           "--frames 0", "--novel-ss 9", "--hole-radius -1", "--offpath -1", "--scene no-such-scene", "--photo-width 0", "--threads -1",
                           "--calibration-px -1", "--photo-yaw 200", "--photo-backoff -1", "--mixed-reach 65"}) {
    RunResult r = run_cli(std::string("gibr ") + args + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    const std::string flag = std::string(args).substr(0, std::string(args).find(' '));
    if (flag != "--scene") {
      EXPECT_NE(r.output.find(flag), std::string::npos) << args << ": " << r.output;
    }
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  // A missing camera file is found as the run starts: exit 2 naming it, nothing written.
  RunResult missing = run_cli("gibr --camera-file " + (dir.path / "nope.json").string() + " --out " + out.string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("nope.json"), std::string::npos) << missing.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace proxima
