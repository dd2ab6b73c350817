// `proxima reflect --method temporal` end to end: results.json carries the documented
// metrics; bad input is exit code 2 with nothing written.
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

namespace {

// Metrics of a 6-frame --compare run on room-reflector (48×32) with `extra` flags; null
// (and a test failure) when the run fails.
nlohmann::json compare_metrics(const std::string& extra) {
  TempDir dir;
  const auto out = dir.path / "run";
  const RunResult r = run_cli("reflect --method temporal --scene room-reflector --path 0 --frames 6 --width 48 "
                              "--height 32 --compare " + extra + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  if (r.exit_code != 0) return nullptr;
  std::ifstream in(out / "results.json");
  return nlohmann::json::parse(in)["metrics"];
}

}  // namespace

// --breakdown splits the temporal error into classes whose contributions add up to the
// MAE; --reference-rays and --lobe-seed-cell run alongside.
TEST(TemporalCli, BreakdownContributionsAddUpToTheMae) {
  const nlohmann::json m = compare_metrics("--breakdown --reference-rays 16 --lobe-seed-cell 0.01");
  ASSERT_FALSE(m.is_null());
  double sum = 0.0;
  int classes = 0;
  for (const auto& [name, value] : m.items())
    if (name.rfind("breakdown_", 0) == 0) sum += value.get<double>(), ++classes;
  EXPECT_EQ(classes, 14);
  EXPECT_GT(m["temporal_mae_avg"].get<double>(), 0.0);
  EXPECT_NEAR(sum, m["temporal_mae_avg"].get<double>(), 1e-6 * (1.0 + sum));
  EXPECT_TRUE(m.contains("seed_noise_mae_avg"));
  EXPECT_TRUE(m.contains("hq_temporal_mae_avg"));
  EXPECT_NEAR(m["lobe_seed_cell"].get<double>(), 0.01, 1e-6);  // stored as float
}

// --edge-rule recompute: reflected-edge pixels are recomputed (counted apart), and the run
// reports the CPU-time speed-up beside the wall-clock one.
TEST(TemporalCli, EdgeRuleRecomputeIsReported) {
  const nlohmann::json m = compare_metrics("--edge-contrast 0.02 --edge-rule recompute");
  ASSERT_FALSE(m.is_null());
  EXPECT_EQ(m["edge_rule_recompute"].get<double>(), 1.0);
  EXPECT_GE(m["edge_pct_avg"].get<double>(), 0.0);
  EXPECT_LE(m["edge_pct_avg"].get<double>(), m["recompute_pct_avg"].get<double>());
  for (const char* name : {"temporal_cpu_ms_avg", "reference_cpu_ms_avg", "speedup_cpu_vs_reference"})
    EXPECT_GT(m[name].get<double>(), 0.0) << name;
}

// --match-extrapolate is reported with the best match's descent steps per reflective pixel
// (no key frame after the first, so later frames have two previous offset buffers).
TEST(TemporalCli, MatchExtrapolateIsReported) {
  // One key frame: the threshold never fires and the cost rule is off.
  const nlohmann::json plain = compare_metrics("--threshold 1 --keyframe-cost 0");
  const nlohmann::json m = compare_metrics("--threshold 1 --keyframe-cost 0 --match-extrapolate");
  ASSERT_FALSE(plain.is_null());
  ASSERT_FALSE(m.is_null());
  EXPECT_EQ(plain["match_extrapolate"].get<double>(), 0.0);
  EXPECT_EQ(m["match_extrapolate"].get<double>(), 1.0);
  EXPECT_EQ(m["keyframes"].get<double>(), 1.0);
  EXPECT_GT(plain["match_steps_per_pixel_avg"].get<double>(), 0.0);
  EXPECT_GT(m["match_steps_per_pixel_avg"].get<double>(), 0.0);
}

}  // namespace proxima
