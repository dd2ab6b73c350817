// `proxima reflect --method layered` (what --layers builds: tests/study/envmap_reflect_test.cpp):
// the layer metrics reach results.json; a bad --layers or --march-steps exits 2 naming the
// flag with nothing written.
#include <gtest/gtest.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_util.h"

namespace proxima {
namespace {

RunResult run(const std::string& args) { return run_cli("reflect " + args); }

const std::string kSmall = " --width 64 --height 48 --cube-size 32 --light-samples 1 --reps 1";

TEST(EnvmapLayeredCli, LayersFlagReachesTheStudy) {
  TempDir dir;
  RunResult r = run("--method layered --scene room-parallax --layers 1" + kSmall + " --out " + dir.path.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir.path / "results.json"));
  EXPECT_EQ(j["metrics"]["layers"].get<double>(), 1.0);
  EXPECT_TRUE(j["metrics"].contains("layer0_shaded_texels"));
  EXPECT_FALSE(j["metrics"].contains("layer1_shaded_texels"));
  EXPECT_TRUE(j["metrics"].contains("layered_fallback_pct"));
}

TEST(EnvmapLayeredCli, BadLayerFlagsExitTwoNamingTheFlag) {
  TempDir dir;
  const std::string out = " --out " + (dir.path / "never").string();
  for (auto [args, flag] : {std::pair{"--layers 0", "--layers"}, std::pair{"--layers 17", "--layers"},
                            std::pair{"--march-steps 0", "--march-steps"}}) {
    RunResult r = run(std::string("--method layered ") + args + kSmall + out);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(flag), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path / "never")) << args;
  }
}

}  // namespace
}  // namespace proxima
