// The command line on hostile and degenerate input: every case exits 0, or 2
// with one line naming the file — never a crash. docs/formats.md says what happens to each.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <string>

#include "cli/cli_util.h"
#include "proxima/core/image_io.h"
#include "test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A small, cheap render of `scene` into dir/out.
RunResult render(const fs::path& scene, const fs::path& out) {
  return run_cli("render --scene " + scene.string() +
                 " --width 32 --height 24 --spp 1 --light-samples 2 --glossy-rays 2 --threads 2 --out " + out.string());
}

double coverage_pct(const fs::path& out) {
  std::ifstream in(out / "results.json");
  return nlohmann::json::parse(in)["metrics"]["coverage_pct"].get<double>();
}

// An OBJ of two triangles of the quad [0, s]² at height 0 (in z) offset by `o`, plus `extra`.
std::string quad_obj(double s, double o, const std::string& extra = "") {
  auto v = [&](double x, double y) {
    return "v " + std::to_string(o + x * s) + " " + std::to_string(o + y * s) + " 0\n";
  };
  return v(0, 0) + v(1, 0) + v(1, 1) + v(0, 1) + "f 1 2 3\nf 1 3 4\n" + extra;
}

struct Case {
  const char* file;
  std::string text;
  int exit_code;        // expected
  const char* message;  // expected on stderr when exit 2
};

TEST(Robustness, DegenerateGeometryRendersOrExitsTwoNeverCrashes) {
  TempDir dir;
  const std::vector<Case> cases = {
      // Zero-area triangles only (repeated and collinear corners): nothing left to render.
      {"zero_area.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\nf 2 2 2\n", 2, "no (non-degenerate) triangles"},
      // The same triangle three times, once reversed: all kept, z-fighting resolved by Embree.
      {"duplicate.obj", quad_obj(1, 0, "f 1 2 3\nf 3 2 1\n"), 0, nullptr},
      // Collinear ones are dropped, the rest renders.
      {"collinear.obj", quad_obj(1, 0, "v 0.5 0 0\nf 1 5 2\n"), 0, nullptr},
      {"huge.obj", quad_obj(1e6, 0), 0, nullptr},
      {"tiny.obj", quad_obj(1e-6, 0), 0, nullptr},
      {"unit_far_from_origin.obj", quad_obj(1, 1e6), 0, nullptr},
      // Float spacing at 1e6 is 0.0625: a millimeter quad there collapses to a point.
      {"tiny_far_from_origin.obj", quad_obj(1e-3, 1e6), 2, "no (non-degenerate) triangles"},
      {"nan.obj", quad_obj(1, 0, "v nan 0 0\nf 1 2 5\n"), 2, "non-finite"},
      {"inf.obj", quad_obj(1, 0, "v 0 -inf 0\nf 1 2 5\n"), 2, "non-finite"},
  };
  for (const Case& c : cases) {
    write_file(dir.path / c.file, c.text);
    const fs::path out = dir.path / (std::string(c.file) + ".out");
    const RunResult r = render(dir.path / c.file, out);
    ASSERT_EQ(r.exit_code, c.exit_code) << c.file << ": " << r.output;
    if (c.exit_code == 2) {
      EXPECT_TRUE(contains(r.output, c.file) && contains(r.output, c.message)) << c.file << ": " << r.output;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.file << ": " << r.output;
      EXPECT_FALSE(fs::exists(out)) << c.file;
    } else {
      // The default camera frames the bounds, so the geometry is in view at every scale.
      EXPECT_GT(coverage_pct(out), 10.0) << c.file;
      const ImageF color = read_exr(out / "color.exr");
      for (float v : color.data()) ASSERT_TRUE(std::isfinite(v)) << c.file;
    }
  }
}

// Coordinates near the float range: the camera and BVH cannot be built; exit 2, not a crash.
TEST(Robustness, CoordinatesNearTheFloatLimitExitCleanly) {
  TempDir dir;
  write_file(dir.path / "extreme.obj", quad_obj(3e38, -1.5e38));
  const RunResult r = render(dir.path / "extreme.obj", dir.path / "out");
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.output;
  if (r.exit_code == 2) {
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

TEST(Robustness, MalformedFileOfEachKindExitsTwoNamingIt) {
  TempDir dir;
  const fs::path d = dir.path;
  write_file(d / "broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n0\n");
  write_file(d / "broken.gltf", R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 7}]})");
  write_file(d / "broken.glb", std::string("glTF\x02\0\0\0\xff\xff\0\0", 12));
  write_file(d / "broken.png", "\x89PNG\r\n\x1a\nnot really");
  write_file(d / "broken.exr", std::string("\x76\x2f\x31\x01\x02\0\0\0garbage", 15));
  write_file(d / "broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
  write_file(d / "textured.json", R"({"materials": [{"name": "m", "texture": "broken.png"}],
                                      "objects": [{"type": "box", "size": [1, 1, 1], "material": "m"}]})");
  write_file(d / "sky.json", R"({"objects": [{"type": "box", "size": [1, 1, 1]}],
      "environment": {"cube": ["broken.exr", "broken.exr", "broken.exr", "broken.exr", "broken.exr", "broken.exr"]}})");
  write_file(d / "meshref.json", R"({"objects": [{"type": "mesh", "file": "broken.ply"}]})");
  // (scene file, file the message must name)
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"broken.ply", "broken.ply"},      {"broken.gltf", "broken.gltf"}, {"broken.glb", "broken.glb"},
      {"broken.obj", "broken.obj"},      {"textured.json", "broken.png"}, {"sky.json", "broken.exr"},
      {"meshref.json", "broken.ply"},
  };
  for (const auto& [scene, named] : cases) {
    const RunResult r = run_cli("info " + (d / scene).string());
    EXPECT_EQ(r.exit_code, 2) << scene << ": " << r.output;
    EXPECT_TRUE(contains(r.output, named)) << scene << ": " << r.output;
    EXPECT_TRUE(contains(r.output, scene)) << scene << ": " << r.output;
  }
  // The scene file itself, and a camera path in one (same reader, its own checks).
  write_file(d / "broken.json", R"({"objects": [{"type": "box", "size": [1, 1, 1]}],)");
  write_file(d / "path.json", R"({"objects": [{"type": "box", "size": [1, 1, 1]}],
      "camera_paths": [{"frames": 3, "keys": [{"time": 1, "position": [0, 0, 5], "target": [0, 0, 0]},
                                              {"time": 0, "position": [0, 0, 4], "target": [0, 0, 0]}]}]})");
  for (const char* scene : {"broken.json", "path.json"}) {
    const RunResult r = run_cli("render --scene " + (d / scene).string() + " --width 8 --height 8 --out " + (d / "o").string());
    EXPECT_EQ(r.exit_code, 2) << scene << ": " << r.output;
    EXPECT_TRUE(contains(r.output, scene)) << scene << ": " << r.output;
    EXPECT_FALSE(fs::exists(d / "o")) << scene;
  }
  // A winged-pair file (visibility --load) and an unsupported mesh format.
  write_file(d / "broken.wp", "proxima-winged-pair 1\nscale 1 polygons 20\nvertices 3\n0 0 0 -1\n");
  RunResult r = run_cli("visibility --scene rooms --frames 1 --width 16 --height 16 --no-oracle --load " +
                        (d / "broken.wp").string() + " --out " + (d / "v").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, (d / "broken.wp").string())) << r.output;
  EXPECT_FALSE(fs::exists(d / "v"));
  write_file(d / "model.fbx", "Kaydara FBX Binary  ");
  r = run_cli("info " + (d / "model.fbx").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "model.fbx: unsupported mesh format")) << r.output;
}

// A FIFO as a texture would block a reader forever; only regular files are read.
TEST(Robustness, DeviceAsTextureIsRejected) {
  TempDir dir;
  write_file(dir.path / "dev.json", R"({"materials": [{"name": "m", "texture": "/dev/zero"}],
                                        "objects": [{"type": "box", "size": [1, 1, 1], "material": "m"}]})");
  const RunResult r = run_cli("info " + (dir.path / "dev.json").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "/dev/zero: not a regular file")) << r.output;
}

TEST(Robustness, TriangleLimitFromFlagAndEnvironment) {
  TempDir dir;
  RunResult r = run_cli("render --scene cornell --max-triangles 10 --out " + (dir.path / "a").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "cornell: ") && contains(r.output, "exceed the limit of 10 (--max-triangles"))
      << r.output;
  EXPECT_FALSE(fs::exists(dir.path / "a"));
  r = run_cli("info cornell", "PROXIMA_MAX_TRIANGLES=10 ");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "PROXIMA_MAX_TRIANGLES")) << r.output;
  r = run_cli("info cornell", "PROXIMA_MAX_TRIANGLES=lots ");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "PROXIMA_MAX_TRIANGLES: must be a positive integer")) << r.output;
  r = run_cli("info cornell --max-memory-mb 0");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "--max-memory-mb")) << r.output;
  EXPECT_EQ(run_cli("info cornell --max-triangles 100000").exit_code, 0);
}

}  // namespace
}  // namespace proxima
