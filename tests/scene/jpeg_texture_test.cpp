// JPEG textures end to end: an OBJ whose .mtl names a .jpg (as furniture libraries ship
// them), a scene file's material texture, and the command line on good and bad JPEGs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>

#include "cli/cli_util.h"
#include "core/jpeg_test.h"
#include "proxima/core/camera.h"
#include "proxima/core/image_io.h"
#include "proxima/scene/load.h"
#include "proxima/scene/scene.h"
#include "test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

constexpr uint8_t kRed[3] = {230, 20, 20}, kBlue[3] = {20, 20, 230};

// 16×16 JPEG: the left half red, the right half blue (8×8 blocks, so the edge is sharp).
std::string red_blue_jpeg() {
  std::vector<uint8_t> px;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) px.push_back(x < 8 ? kRed[c] : kBlue[c]);
  return encode_jpeg(px, 16, 16);
}

// A unit quad with uvs covering the texture, its .mtl naming `texture`.
fs::path write_textured_obj(const fs::path& dir, const std::string& texture) {
  write_file(dir / "quad.mtl", "newmtl painted\nKd 1 1 1\nmap_Kd " + texture + "\n");
  write_file(dir / "quad.obj",
             "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
             "usemtl painted\nf 1/1 2/2 3/3 4/4\n");
  return dir / "quad.obj";
}

vec3 linear(const uint8_t (&srgb)[3]) {
  return {srgb_to_linear(srgb[0] / 255.0f), srgb_to_linear(srgb[1] / 255.0f), srgb_to_linear(srgb[2] / 255.0f)};
}

TEST(JpegTexture, ObjWithJpegTextureLoadsAndTheTextureColorsTheSurface) {
  TempDir dir;
  write_file(dir.path / "maps" / "paint.jpg", red_blue_jpeg());
  const fs::path obj = write_textured_obj(dir.path, "maps/paint.jpg");
  const Scene s = load_scene(obj.string());
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].image.width(), 16);
  ASSERT_EQ(s.triangles.size(), 2u);
  const Material& m = s.materials[s.triangle_material[0]];
  EXPECT_EQ(m.name, "painted");
  ASSERT_EQ(m.diffuse_texture, 0);
  // Every sampled surface point away from the red/blue edge has its half's color.
  int checked = 0;
  for (uint32_t t = 0; t < 2; ++t)
    for (float u = 0.05f; u < 1.0f; u += 0.1f)
      for (float v = 0.05f; u + v < 1.0f; v += 0.1f) {
        const vec2 uv = triangle_uv(s, t, u, v);
        if (std::abs(uv.x - 0.5f) < 0.1f || uv.x < 0.05f || uv.x > 0.95f) continue;  // edge, wrap blend
        const vec3 want = uv.x < 0.5f ? linear(kRed) : linear(kBlue);
        const vec3 got = surface_diffuse(s, t, u, v);
        EXPECT_LT(glm::distance(got, want), 0.02f) << "uv " << uv.x << " " << uv.y;
        ++checked;
      }
  EXPECT_GT(checked, 20);
}

TEST(JpegTexture, SceneFileMaterialTextureMayBeAJpeg) {
  TempDir dir;
  write_file(dir.path / "paint.jpg", red_blue_jpeg());
  write_file(dir.path / "s.json",
             R"({"materials": [{"name": "p", "diffuse": 1, "texture": "paint.jpg"}],
                 "objects": [{"type": "plane", "size": [1, 1], "material": "p"}]})");
  const Scene s = load_scene((dir.path / "s.json").string());
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].image.height(), 16);
  EXPECT_LT(glm::distance(sample_texture(s.textures[0], vec2(0.25f, 0.5f)), linear(kRed)), 0.02f);
}

TEST(JpegTexture, CliInfoOnObjWithJpegTextureExitsZero) {
  TempDir dir;
  write_file(dir.path / "paint.jpg", red_blue_jpeg());
  const fs::path obj = write_textured_obj(dir.path, "paint.jpg");
  const RunResult r = run_cli("info " + obj.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex("textures: +1\n"))) << r.output;
}

// A texture that exists but cannot be decoded is an error (a missing one only warns):
// exit 2, one line naming the OBJ, the material and the JPEG.
TEST(JpegTexture, CliTruncatedJpegTextureExitsTwoNamingTheFile) {
  TempDir dir;
  const std::string full = red_blue_jpeg();
  write_file(dir.path / "cut.jpg", full.substr(0, full.size() / 2));
  const fs::path obj = write_textured_obj(dir.path, "cut.jpg");
  const RunResult r = run_cli("info " + obj.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "quad.obj: material 'painted': " + (dir.path / "cut.jpg").string() +
                                     ": cannot read JPEG: "))
      << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(JpegTexture, CliJpegTextureDeclaring60000SquareExitsTwoNamingTheFile) {
  TempDir dir;
  write_file(dir.path / "huge.jpg", with_declared_size(red_blue_jpeg(), 60000, 60000));
  const fs::path obj = write_textured_obj(dir.path, "huge.jpg");
  const RunResult r = run_cli("render --width 16 --height 16 --out " + (dir.path / "out").string() +
                              " --scene " + obj.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, (dir.path / "huge.jpg").string() + ": image of 60000x60000 pixels exceeds the maximum side " +
                                     std::to_string(kMaxImageSide)))
      << r.output;
  EXPECT_FALSE(fs::exists(dir.path / "out" / "color.png"));
}

}  // namespace
}  // namespace proxima
