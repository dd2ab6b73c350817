// `proxima shadows`: bad input exits 2 naming the flag and writes nothing; a small run
// writes results.json with the documented metric names and the images.
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
  };
  for (const auto& [args, flag] : cases) {
    const RunResult r = run_cli("shadows " + std::string(args) + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(flag), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  const RunResult r = run_cli("shadows --scene no_such_scene --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ShadowsCli, WritesTheIssueMetricsAndImages) {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const RunResult r = run_cli("shadows --scene city --sampling nrr --light-samples 2 --ref-res 48 --out-res 32 "
                              "--shadow-res 64 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto json = nlohmann::json::parse(std::ifstream(std::filesystem::path(out) / "results.json"));
  const auto& m = json["metrics"];
  for (const char* k : {"intensity_error_mean", "intensity_error_max", "visibility_error_mean", "visibility_error_max",
                        "time_reference_ms", "time_reconstruct_ms", "time_shadow_ms", "visibility_error_rays_mean"})
    EXPECT_TRUE(m.contains(k)) << k;
  EXPECT_LE(m["intensity_error_mean"].get<double>(), m["visibility_error_mean"].get<double>());
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "nrr_error.png"));
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "geometry_shadow.png"));
}

}  // namespace
}  // namespace proxima
