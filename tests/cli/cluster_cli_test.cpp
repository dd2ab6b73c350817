// `proxima reflect --method cluster` end to end (smoke): flags reach the study, results.json
// carries the published metrics, bad input is exit code 2 with nothing written. The study's
// behaviour is tested in tests/study/cluster_reflect_test.cpp.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/cli_util.h"

namespace proxima {

namespace {

int exit_code(const std::string& args) { return run_cli(args).exit_code; }

}  // namespace

TEST(ClusterCli, CompareWritesTheIssueMetrics) {
  TempDir dir;
  const auto out = dir.path / "run";
  ASSERT_EQ(exit_code("reflect --method cluster --scene room-reflector --path 0 --frames 2 --width 48 --height 32 --ss 1 "
                    "--cube-size 16 --compare --out " + out.string()),
            0);
  std::ifstream in(out / "results.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* name : {"cluster_mae_r", "cluster_mae_g", "cluster_mae_b", "occlusion_error_pct_avg",
                           "occlusion_error_pct_max", "clusters_avg", "cluster_ms_avg", "reference_ms_avg",
                           "reference_dynamic_ms_avg"})
    EXPECT_TRUE(j["metrics"].contains(name)) << name;
  EXPECT_GE(j["metrics"]["clusters_avg"].get<double>(), 1.0);
  EXPECT_EQ(j["metrics"]["frames"].get<double>(), 2.0);
  for (const char* name : {"reference.png", "envmap.png", "error_cluster.png", "error_envmap.png", "cluster.png"})
    EXPECT_TRUE(std::filesystem::exists(out / name)) << name;
}

TEST(ClusterCli, OneSceneCameraOrOnePathFrame) {
  TempDir dir;
  for (const std::string& pick : {std::string("--camera 0"), std::string("--path 0 --frame 3")}) {
    const auto out = dir.path / (pick[2] == 'c' ? "camera" : "frame");
    ASSERT_EQ(exit_code("reflect --method cluster --scene room-reflector " + pick + " --width 40 --ss 1 --out " +
                      out.string()),
              0)
        << pick;
    std::ifstream in(out / "results.json");
    nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["metrics"]["frames"].get<double>(), 1.0) << pick;
    EXPECT_TRUE(std::filesystem::exists(out / "cluster.png")) << pick;
  }
}

TEST(ClusterCli, BadInputIsExitCodeTwoAndWritesNothing) {
  TempDir dir;
  const auto out = dir.path / "bad";
  EXPECT_EQ(exit_code("reflect --method cluster --scene room-reflector --ss 0 --out " + out.string()), 2);
  EXPECT_EQ(exit_code("reflect --method cluster --scene room-reflector --path nope --out " + out.string()), 2);
  EXPECT_EQ(exit_code("reflect --method cluster --scene room-reflector --camera nope --out " + out.string()), 2);
  EXPECT_EQ(exit_code("reflect --method cluster --scene room-reflector --path 0 --frame 100000 --out " + out.string()), 2);
  EXPECT_EQ(exit_code("reflect --method cluster --scene room-reflector --gloss-rays 5000 --out " + out.string()), 2);
  EXPECT_EQ(exit_code("reflect --method clusters --scene room-reflector --out " + out.string()), 2);
  EXPECT_EQ(exit_code("reflect --method cluster --scene room-reflector --march-block -1 --out " + out.string()), 2);
  EXPECT_EQ(exit_code("reflect --method cluster --scene room-reflector --second-layer maybe --out " + out.string()), 2);
  // There is no reflect-cluster subcommand (the method is `reflect --method cluster`).
  EXPECT_EQ(exit_code("reflect-cluster --scene room-reflector --out " + out.string()), 2);
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace proxima
