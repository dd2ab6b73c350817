// `proxima sample` (the sampling study's command; the study is tested in
// tests/study/sampling_test.cpp): bad input exits 2 naming the flag and writes nothing; a
// small run writes results.json, the per-image files and the tables.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_util.h"

namespace proxima {
namespace {

TEST(SamplingCli, BadInputExitsTwoNamingTheFlag) {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const std::pair<const char*, const char*> cases[] = {
      {"--method bogus", "--method"},          {"--views hexagon", "--views"}, {"--frames -1", "--frames"},
      {"--redundancy strict", "--redundancy"}, {"--width 0", "--width"},       {"--radius -1", "--radius"},
      {"--camera nowhere", "--camera"},        {"--threads -1", "--threads"},
  };
  for (const auto& [args, flag] : cases) {
    const RunResult r = run_cli("sample --scene city " + std::string(args) + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(flag), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  const RunResult r = run_cli("sample --scene no_such_scene --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no_such_scene"), std::string::npos) << r.output;
}

TEST(SamplingCli, WritesResultsAndImages) {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const RunResult r =
      run_cli("sample --scene city --method nrr-pixel --views segment --width 48 --frames 3 --reps 1 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto json = nlohmann::json::parse(std::ifstream(std::filesystem::path(out) / "results.json"));
  const auto& m = json["metrics"];
  for (const char* name : {"redundant_pct_1", "occluded_pct_1", "useful_pct_1", "available_avg_pct", "time_ms"})
    EXPECT_TRUE(m.contains(name)) << name;
  EXPECT_EQ(json["command"][1], "sample");
  for (const char* file : {"nrr-pixel_0_color.png", "nrr-pixel_1_depth.exr", "nrr-pixel_1_id.exr",
                           "nrr-pixel_1_occluded.png"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / file)) << file;
  EXPECT_NE(r.output.find("| nrr-pixel |"), std::string::npos);
}

}  // namespace
}  // namespace proxima
