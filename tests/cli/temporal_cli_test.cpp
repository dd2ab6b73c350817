// `proxima reflect --method temporal` end to end (smoke): flags reach the study, results.json
// carries the published metrics and the per-frame table, bad input is exit code 2 with
// nothing written. The study's behaviour is tested in tests/study/temporal_reflect_test.cpp.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/cli_util.h"

namespace proxima {

TEST(TemporalCli, CompareWritesTheIssueMetrics) {
  TempDir dir;
  const auto out = dir.path / "run";
  const RunResult r = run_cli("reflect --method temporal --scene room-reflector --path 0 --frames 6 --width 48 "
                              "--height 32 --threshold 0.3 --compare --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "results.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* name : {"temporal_mae_avg", "direct_mae_avg", "recompute_pct_avg", "keyframe_interval_avg",
                           "temporal_ms_avg", "reference_ms_avg", "speedup_vs_reference"})
    EXPECT_TRUE(j["metrics"].contains(name)) << name;
  EXPECT_EQ(j["metrics"]["frames"].get<double>(), 6.0);
  EXPECT_GE(j["metrics"]["keyframes"].get<double>(), 1.0);
  bool per_frame = false;
  for (const auto& t : j["tables"])
    if (t["title"] == "Per frame") per_frame = t["rows"].size() == 6;
  EXPECT_TRUE(per_frame);
  EXPECT_NE(r.output.find("Table 23"), std::string::npos);
}

TEST(TemporalCli, BadInputIsExitCodeTwoAndWritesNothing) {
  TempDir dir;
  const auto out = dir.path / "bad";
  const std::string base = "reflect --method temporal --scene room-reflector --width 32 --height 32 ";
  for (const std::string& args : {base + "--out " + out.string(),  // no --path
                                  base + "--path nope --out " + out.string(),
                                  base + "--path 0 --threshold 1.5 --out " + out.string(),
                                  base + "--path 0 --stretch-limit 0.5 --out " + out.string(),
                                  base + "--path 0 --spread-limit 0.5 --out " + out.string(),
                                  base + "--path 0 --curved-contrast -1 --out " + out.string(),
                                  base + "--path 0 --frames -1 --out " + out.string(),
                                  base + "--path 0 --frame-step 0 --out " + out.string(),
                                  base + "--path 0 --glossy-rays 5000 --out " + out.string(),
                                  base + "--camera 0 --out " + out.string(),
                                  base + "--path 0 --frame 3 --out " + out.string(),
                                  base + "--path 0 --lobe-seed-cell -1 --out " + out.string(),
                                  base + "--path 0 --depth-discontinuity 0 --out " + out.string(),
                                  base + "--path 0 --compare --reference-rays -1 --out " + out.string(),
                                  base + "--path 0 --breakdown --out " + out.string(),
                                  base + "--path 0 --edge-contrast -1 --out " + out.string(),
                                  base + "--path 0 --edge-rule blend --out " + out.string(),
                                  base + "--path 0 --blend-error -0.1 --out " + out.string(),
                                  base + "--path 0 --blend-error nan --out " + out.string(),
                                  base + "--path 0 --keyframe-cost -1 --out " + out.string(),
                                  base + "--path 0 --keyframe-cost inf --out " + out.string()}) {
    const RunResult r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("--"), std::string::npos) << r.output;  // names the flag
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace proxima
