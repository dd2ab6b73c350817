// `proxima reflect` end to end (the figures themselves: tests/study/envmap_reflect_test.cpp):
// one run writes results.json, every method's images and the table; bad input exits 2
// naming the flag with nothing written.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_util.h"

namespace proxima {
namespace {

RunResult run(const std::string& args) { return run_cli("reflect " + args); }

const std::string kSmall = " --width 64 --height 48 --cube-size 32 --light-samples 1 --reps 1";

TEST(ReflectCli, CompareWritesEveryMethodsMetricsAndImages) {
  TempDir dir;
  RunResult r = run("--scene room-reflector --compare" + kSmall + " --out " + dir.path.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir.path / "results.json"));
  for (const char* m : {"envmap", "rectified", "average", "layered", "boxprobe", "reference"}) {
    ASSERT_TRUE(j["metrics"].contains(std::string(m) + "_mae")) << m;
    ASSERT_TRUE(j["metrics"].contains(std::string(m) + "_ms")) << m;
    EXPECT_TRUE(std::filesystem::exists(dir.path / (std::string(m) + ".png"))) << m;
    EXPECT_EQ(std::filesystem::exists(dir.path / ("error_" + std::string(m) + ".png")), std::string(m) != "reference")
        << m;
  }
  EXPECT_EQ(j["images"].size(), 11u);
  EXPECT_NE(r.output.find("| rectified |"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("results: "), std::string::npos) << r.output;
}

TEST(ReflectCli, BadInputExitsTwoNamingTheFlag) {
  TempDir dir;
  const std::string out = " --out " + (dir.path / "never").string();
  for (auto [args, flag] : {std::pair{"--method mirror", "--method: 'mirror' is not one of envmap, rectified, "
                                                         "average, layered, boxprobe, reference, cluster, ssr, temporal"},
                            std::pair{"--d-e 0", "--d-e"}, std::pair{"--edge grey", "--edge"},
                            std::pair{"--cube-size 0", "--cube-size"}, std::pair{"--threads -1", "--threads"},
                            std::pair{"--scene cornell-nope", "cornell-nope"},
                            std::pair{"--camera nowhere", "--camera"},
                            std::pair{"--scene nest", "--scene: 'nest' has no reflective object"},
                            std::pair{"--method cluster --edge grey", "--edge"}}) {
    RunResult r = run(std::string(args) + kSmall + out);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(flag), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path / "never")) << args;
  }
}

}  // namespace
}  // namespace proxima
