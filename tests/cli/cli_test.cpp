// The command line end to end: exit codes, error messages naming the flag/file, no
// partial outputs, determinism across --threads, results.json contents.
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/cli_util.h"
#include "proxima/core/image_io.h"
#include "proxima/scene/builtin_scenes.h"
#include "test_util.h"

namespace proxima {
namespace {

TEST(Cli, HelpOnEverySubcommand) {
  for (const char* sub : {"scenes", "info", "render", "bench", "bench trace", "bench raster", "bench techniques", "bench view", "demo", "reflect", "shadows", "view", "gibr"}) {
    RunResult r = run_cli(std::string(sub) + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub << ": " << r.output;
  }
}

TEST(Cli, ScenesListsTheBuiltins) {
  RunResult r = run_cli("scenes");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* name : {"cornell", "room-reflector", "living-room", "bathroom"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name;
}

TEST(Cli, UnknownFlagExitsWithTwoNamingTheFlag) {
  RunResult r = run_cli("render --out /tmp/x --bogus-flag 3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--bogus-flag"), std::string::npos) << r.output;
}

TEST(Cli, UnknownSceneExitsWithTwoAndWritesNothing) {
  TempDir dir;
  auto out = dir.path / "out";
  RunResult r = run_cli("render --scene no-such-scene --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no-such-scene"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, BadResolutionExitsWithTwoNamingTheFlag) {
  TempDir dir;
  for (const char* size : {"--width 0", "--height -5", "--width 100000"}) {
    RunResult r = run_cli(std::string("render --scene cornell ") + size + " --out " + (dir.path / "o").string());
    EXPECT_EQ(r.exit_code, 2) << size << ": " << r.output;
    EXPECT_NE(r.output.find("--width"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
  }
  RunResult r = run_cli("render --scene cornell --width abc --out " + (dir.path / "o").string());
  EXPECT_EQ(r.exit_code, 2);
}

TEST(Cli, MissingAndMalformedFilesExitWithTwoNamingTheFile) {
  TempDir dir;
  auto bad_json = dir.path / "broken.json";
  write_file(bad_json, "{ \"objects\": [ ");
  auto bad_obj = dir.path / "broken.obj";
  write_file(bad_obj, "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  for (const auto& file : {dir.path / "missing.obj", bad_json, bad_obj}) {
    RunResult r = run_cli("info " + file.string());
    EXPECT_EQ(r.exit_code, 2) << file << ": " << r.output;
    EXPECT_NE(r.output.find(file.filename().string()), std::string::npos) << r.output;
  }
}

TEST(Cli, InfoCountsDroppedDegenerateTriangles) {
  TempDir dir;
  auto obj = dir.path / "degenerate.obj";
  write_file(obj,
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
             "f 1 2 3\n"   // fine
             "f 1 2 4\n"   // collinear: zero area
             "f 1 1 3\n");  // repeated vertex
  RunResult r = run_cli("info " + obj.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("triangles:           1\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("dropped degenerate:  2"), std::string::npos) << r.output;
}

TEST(Cli, RenderWritesItsImagesAndResults) {
  TempDir dir;
  RunResult r = run_cli("render --scene cornell --width 64 --height 48 --spp 2 --glossy-rays 4 --seed 9 --threads 2 "
                        "--out " + dir.path.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(dir.path / "results.json");
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["threads"], 2);
  EXPECT_EQ(j["command"][1], "render");
  EXPECT_GT(j["metrics"]["coverage_pct"].get<double>(), 50.0);  // the cornell box fills most of the view
  EXPECT_LE(j["metrics"]["coverage_pct"].get<double>(), 100.0);
  for (const char* f : {"color.png", "color.exr", "depth.exr", "normal.exr", "id.exr"})
    EXPECT_TRUE(std::filesystem::exists(dir.path / f)) << f;
  const ImageF depth = read_exr(dir.path / "depth.exr");
  EXPECT_EQ(depth.width(), 64);
  EXPECT_EQ(depth.height(), 48);
  r = run_cli("render --scene cornell --spp 0 --out " + (dir.path / "bad").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--spp"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "bad"));
}

TEST(Cli, BenchTraceWritesTheNamedMetrics) {
  TempDir dir;
  RunResult r = run_cli("bench trace --scene cornell --width 64 --height 64 --reps 1 --out " + dir.path.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(dir.path / "results.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* m : {"bvh_build_ms", "primary_mrays_s", "reflection_mrays_s", "primary_mrays_s_1t"}) {
    ASSERT_TRUE(j["metrics"].contains(m)) << m;
    EXPECT_GT(j["metrics"][m].get<double>(), 0.0) << m;
  }
  EXPECT_EQ(j["command"][1], "bench");
  EXPECT_TRUE(j.contains("commit"));
  EXPECT_TRUE(j.contains("build"));
}

TEST(Cli, BenchRasterWritesTheNamedMetrics) {
  TempDir dir;
  // The agreement pass is tested on the study (tests/study/raster_bench_test.cpp).
  RunResult r = run_cli("bench raster --scene cornell --width 96 --height 96 --reps 1 --skip-agreement --out " +
                        dir.path.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(dir.path / "results.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* m : {"raster_ms_depth_id", "tris_per_s"}) EXPECT_GT(j["metrics"][m].get<double>(), 0.0) << m;
  // llvmpipe figures are present, as numbers when the optional harness ran, else null.
  for (const char* m : {"llvmpipe_ms_depth_id", "speedup_vs_llvmpipe"}) EXPECT_TRUE(j["metrics"].contains(m)) << m;
  EXPECT_FALSE(j["metrics"].contains("id_agreement_pct"));
  r = run_cli("bench raster --scene cornell --reps 0 --out " + (dir.path / "bad").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--reps"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "bad"));
}

TEST(Cli, DemoWritesResultsAndAReportShowingThem) {
  TempDir dir;
  // The two in-process sections; the technique sections run for minutes (make demo).
  RunResult r = run_cli("demo --only reference,raster --width 32 --height 32 --out " + dir.path.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(dir.path / "results.json");
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_GE(j["metrics"]["id_agreement_with_ties_pct"].get<double>(), 99.9);
  for (const auto& [role, file] : j["images"].items())
    EXPECT_TRUE(std::filesystem::exists(dir.path / file.get<std::string>())) << role;
  std::ifstream page(dir.path / "index.html");
  std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  for (const auto& s : j["sections"]) EXPECT_NE(html.find(s["title"].get<std::string>()), std::string::npos);
  EXPECT_GT(j["metrics"]["demo_seconds"].get<double>(), 0.0);
  // Progress goes to stderr as plain lines when it is not a terminal.
  EXPECT_NE(r.output.find("rasterizer vs Embree 1/1 done"), std::string::npos) << r.output;

  r = run_cli("demo --only nope --out " + (dir.path / "x").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--only"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "x"));
}

TEST(Cli, CameraAndPathFlagsAreValidated) {
  TempDir dir;
  RunResult r = run_cli("render --scene cornell --camera 99 --width 16 --height 16 --out " + dir.path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--camera"), std::string::npos) << r.output;
  r = run_cli("render --scene cornell --path nope --width 16 --height 16 --out " + dir.path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--path"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace proxima
