// `proxima sample`: bad input exits 2 naming the flag and writes nothing; a small run
// writes results.json with the documented metric names and the per-image files.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

#include "test_util.h"

namespace proxima {
namespace {

struct RunResult {
  int exit_code;
  std::string output;  // stdout + stderr
};

RunResult run_cli(const std::string& args) {
  const std::string cmd = std::string(PROXIMA_CLI_PATH) + " " + args + " 2>&1 </dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string output;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) output.append(buf.data(), n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

TEST(SamplingCli, BadInputExitsTwoNamingTheFlag) {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const std::pair<const char*, const char*> cases[] = {
      {"--method bogus", "--method"},    {"--views hexagon", "--views"}, {"--frames -1", "--frames"},
      {"--redundancy strict", "--redundancy"}, {"--width 0", "--width"}, {"--radius -1", "--radius"},
  };
  for (const auto& [args, flag] : cases) {
    const RunResult r = run_cli("sample " + std::string(args) + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(flag), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  const RunResult r = run_cli("sample --scene no_such_scene --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no_such_scene"), std::string::npos) << r.output;
}

TEST(SamplingCli, WritesTheIssueMetricsAndImages) {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const RunResult r =
      run_cli("sample --scene city --method nrr-pixel --views segment --width 48 --frames 3 --reps 1 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto json = nlohmann::json::parse(std::ifstream(std::filesystem::path(out) / "results.json"));
  const auto& m = json["metrics"];
  for (const char* name : {"redundant_pct_0", "redundant_pct_1", "occluded_pct_1", "useful_pct_1", "available_avg_pct",
                           "available_min_pct", "time_ms"})
    EXPECT_TRUE(m.contains(name)) << name;
  EXPECT_EQ(m["redundant_pct_1"].get<double>(), 0.0);  // NRR under its own definition
  EXPECT_FALSE(m.contains("redundant_pct_2"));         // a segment has two views
  for (const char* file : {"nrr-pixel_0_color.png", "nrr-pixel_1_depth.exr", "nrr-pixel_1_id.exr",
                           "nrr-pixel_1_occluded.png"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / file)) << file;
  EXPECT_NE(r.output.find("| nrr-pixel |"), std::string::npos);
}

}  // namespace
}  // namespace proxima
