// `proxima shadows` (the soft-shadow study's command; the study is tested in
// tests/study/shadows_test.cpp): bad input exits 2 naming the flag and writes nothing; a
// small run writes results.json and the images.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_util.h"

namespace proxima {
namespace {

TEST(ShadowsCli, BadInputExitsTwoNamingTheFlag) {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const std::pair<const char*, const char*> cases[] = {
      {"--sampling bogus", "--sampling"},        {"--light-size 0", "--light-size"},
      {"--light-size -1", "--light-size"},       {"--light-samples 0", "--light-samples"},
      {"--ref-res 2", "--ref-res"},              {"--out-res 100000", "--out-res"},
      {"--shadow-res 0", "--shadow-res"},        {"--redundancy strict", "--redundancy"},
      {"--reconstruction points", "--reconstruction"}, {"--threads -2", "--threads"},
      {"--camera nowhere", "--camera"},
  };
  for (const auto& [args, flag] : cases) {
    const RunResult r = run_cli("shadows --scene city " + std::string(args) + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(flag), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  const RunResult r = run_cli("shadows --scene no_such_scene --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ShadowsCli, WritesResultsAndImages) {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const RunResult r = run_cli("shadows --scene city --sampling nrr --light-samples 2 --ref-res 48 --out-res 32 "
                              "--shadow-res 64 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto json = nlohmann::json::parse(std::ifstream(std::filesystem::path(out) / "results.json"));
  const auto& m = json["metrics"];
  for (const char* k : {"intensity_error_mean", "visibility_error_max", "time_shadow_ms", "visibility_error_rays_mean"})
    EXPECT_TRUE(m.contains(k)) << k;
  EXPECT_EQ(json["command"][1], "shadows");
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "nrr_error.png"));
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "geometry_shadow.png"));
  EXPECT_NE(r.output.find("| nrr |"), std::string::npos);
}

}  // namespace
}  // namespace proxima
