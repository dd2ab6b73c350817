// Same image bits for --threads 1 and --threads 2 (issue 13; DESIGN.md determinism) from
// every command that writes images, on every built-in scene the command accepts, at small
// sizes. `render` is covered by Cli.RenderIsIdenticalForOneAndTwoThreadsOnEveryBuiltinScene.
// Every image file of the output directory (PNG, EXR, SVG) must be byte-identical; a scene
// a command refuses (exit 2, e.g. no reflector, no camera path) must be refused alike.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cli/cli_util.h"
#include "proxima/scene/builtin_scenes.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

std::map<std::string, std::string> image_files(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string ext = e.path().extension().string();
    if (ext != ".png" && ext != ".exr" && ext != ".svg") continue;
    std::ifstream in(e.path(), std::ios::binary);
    files[e.path().filename().string()] = std::string(std::istreambuf_iterator<char>(in), {});
  }
  return files;
}

// Runs `command --scene S ARGS` at 1 and 2 threads for each scene; returns how many scenes
// produced images.
int expect_same_bits(const std::string& command, const std::vector<std::string>& scenes, const std::string& args) {
  int compared = 0;
  for (const std::string& scene : scenes) {
    SCOPED_TRACE(command + " --scene " + scene);
    TempDir dir;
    const std::string common = " --scene " + scene + " " + args + " --out ";
    const RunResult a = run_cli(command + " --threads 1" + common + (dir.path / "t1").string());
    const RunResult b = run_cli(command + " --threads 2" + common + (dir.path / "t2").string());
    if (a.exit_code != b.exit_code) {
      ADD_FAILURE() << "exit " << a.exit_code << " vs " << b.exit_code << "\n" << a.output << "\n" << b.output;
      continue;
    }
    if (a.exit_code == 2) continue;  // the command does not apply to this scene
    if (a.exit_code != 0) {
      ADD_FAILURE() << a.output;
      continue;
    }
    const auto fa = image_files(dir.path / "t1"), fb = image_files(dir.path / "t2");
    EXPECT_FALSE(fa.empty());
    EXPECT_EQ(fa.size(), fb.size());
    for (const auto& [name, bytes] : fa) {
      EXPECT_TRUE(fb.count(name) && bytes == fb.at(name)) << name << " differs between 1 and 2 threads";
    }
    ++compared;
  }
  return compared;
}

std::vector<std::string> all_scenes() {
  std::vector<std::string> names;
  for (const BuiltinSceneInfo& s : builtin_scenes()) names.push_back(s.name);
  return names;
}

TEST(ThreadDeterminism, SampleOnEveryBuiltinScene) {
  EXPECT_EQ(expect_same_bits("sample", all_scenes(),
                             "--method conventional,peeling,nrr-pixel,nrr-visibility --width 16 --frames 2 --reps 1"),
            int(all_scenes().size()));
}

TEST(ThreadDeterminism, ReflectOnEveryBuiltinSceneWithAReflector) {
  EXPECT_GE(expect_same_bits("reflect", all_scenes(),
                             "--compare --width 24 --height 16 --cube-size 8 --light-samples 1 --glossy-rays 2 --reps 1"),
            4);
}

TEST(ThreadDeterminism, ReflectClusterOnEveryBuiltinSceneWithAPath) {
  EXPECT_GE(expect_same_bits("reflect", all_scenes(),
                             "--method cluster --compare --frames 2 --width 24 --height 16 --ss 1 --gloss-rays 2 "
                             "--light-samples 1 --reps 1"),
            2);
}

TEST(ThreadDeterminism, ReflectTemporalOnEveryBuiltinSceneWithAPath) {
  EXPECT_GE(expect_same_bits("reflect", all_scenes(),
                             "--method temporal --path 0 --compare --frames 3 --width 24 --height 16 "
                             "--glossy-rays 2 --light-samples 1"),
            2);
}

TEST(ThreadDeterminism, ShadowsOnTheSamplingScenes) {
  const std::vector<std::string> scenes = {"cornell", "nest", "grass", "city", "tree"};
  EXPECT_GE(expect_same_bits("shadows", scenes,
                             "--sampling nrr,conventional,peeling --ref-res 32 --out-res 24 --shadow-res 32 "
                             "--light-samples 2"),
            4);
}

TEST(ThreadDeterminism, VisibilityOnEveryVisibilityModel) {
  const std::vector<std::string> models = {"rooms", "maze", "arena", "vcity", "floor", "building"};
  EXPECT_EQ(expect_same_bits("visibility", models, "--frames 2 --width 32 --height 24"), int(models.size()));
}

}  // namespace
}  // namespace proxima
