// `proxima reflect` end to end: the documented metrics, images, bad input → exit 2
// naming the flag with nothing written, identical images for any --threads.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "proxima/core/image_io.h"
#include "test_util.h"

namespace proxima {
namespace {

struct RunResult {
  int exit_code;
  std::string output;  // stdout + stderr
};

RunResult run(const std::string& args) {
  std::string cmd = std::string(PROXIMA_CLI_PATH) + " reflect " + args + " 2>&1 </dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string output;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) output.append(buf.data(), n);
  int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

const std::string kSmall = " --width 64 --height 48 --cube-size 32 --light-samples 1 --reps 1";

TEST(ReflectCli, CompareWritesEveryMethodsMetrics) {
  TempDir dir;
  RunResult r = run("--scene room-reflector --compare" + kSmall + " --out " + dir.path.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir.path / "results.json"));
  for (const char* m : {"envmap", "rectified", "average", "layered", "reference"}) {
    ASSERT_TRUE(j["metrics"].contains(std::string(m) + "_mae")) << m;
    ASSERT_TRUE(j["metrics"].contains(std::string(m) + "_ms")) << m;
    EXPECT_GT(j["metrics"][std::string(m) + "_ms"].get<double>(), 0.0) << m;
    EXPECT_TRUE(std::filesystem::exists(dir.path / (std::string(m) + ".png"))) << m;
  }
  EXPECT_EQ(j["metrics"]["reference_mae"].get<double>(), 0.0);
  EXPECT_GT(j["metrics"]["envmap_mae"].get<double>(), j["metrics"]["rectified_mae"].get<double>());
  EXPECT_GT(j["metrics"]["reflector_pixels"].get<double>(), 100.0);
  EXPECT_NE(r.output.find("| rectified |"), std::string::npos) << r.output;
}

TEST(ReflectCli, BadInputExitsTwoNamingTheFlag) {
  TempDir dir;
  const std::string out = " --out " + (dir.path / "never").string();
  for (auto [args, flag] : {std::pair{"--method mirror", "--method"}, std::pair{"--d-e 0", "--d-e"},
                            std::pair{"--edge grey", "--edge"}, std::pair{"--cube-size 0", "--cube-size"},
                            std::pair{"--scene cornell-nope", "cornell-nope"}}) {
    RunResult r = run(std::string(args) + kSmall + out);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(flag), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path / "never")) << args;
  }
}

TEST(ReflectCli, ImagesDoNotDependOnThreads) {
  TempDir a, b;
  ASSERT_EQ(run("--method layered --scene room-parallax --threads 1" + kSmall + " --out " + a.path.string())
                .exit_code,
            0);
  ASSERT_EQ(run("--method layered --scene room-parallax --threads 2" + kSmall + " --out " + b.path.string())
                .exit_code,
            0);
  EXPECT_TRUE(read_image_linear(a.path / "layered.png") == read_image_linear(b.path / "layered.png"));
}

}  // namespace
}  // namespace proxima
