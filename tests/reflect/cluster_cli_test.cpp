// `proxima reflect-cluster` end to end: results.json carries the metrics issue 7 names;
// bad input is exit code 2 with nothing written.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "test_util.h"

namespace proxima {

namespace {

int run_cli(const std::string& args) {
  std::string cmd = std::string(PROXIMA_CLI_PATH) + " " + args + " >/dev/null 2>&1 </dev/null";
  int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(ClusterCli, CompareWritesTheIssueMetrics) {
  TempDir dir;
  const auto out = dir.path / "run";
  ASSERT_EQ(run_cli("reflect-cluster --scene room-reflector --frames 2 --width 48 --height 32 --ss 1 --compare --out " +
                    out.string()),
            0);
  std::ifstream in(out / "results.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* name : {"cluster_mae_r", "cluster_mae_g", "cluster_mae_b", "occlusion_error_pct_avg",
                           "occlusion_error_pct_max", "clusters_avg", "cluster_ms_avg", "reference_ms_avg",
                           "reference_dynamic_ms_avg"})
    EXPECT_TRUE(j["metrics"].contains(name)) << name;
  EXPECT_GE(j["metrics"]["clusters_avg"].get<double>(), 1.0);
  EXPECT_TRUE(std::filesystem::exists(out / "reference.png"));
}

TEST(ClusterCli, BadInputIsExitCodeTwoAndWritesNothing) {
  TempDir dir;
  const auto out = dir.path / "bad";
  EXPECT_EQ(run_cli("reflect-cluster --scene room-reflector --ss 0 --out " + out.string()), 2);
  EXPECT_EQ(run_cli("reflect-cluster --scene room-reflector --path nope --out " + out.string()), 2);
  EXPECT_EQ(run_cli("reflect-cluster --scene room-reflector --gloss-rays 5000 --out " + out.string()), 2);
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace proxima
