#include "proxima/scene/load.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "proxima/core/error.h"
#include "proxima/scene/builtin_scenes.h"
#include "test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

TEST(LoadTest, UnknownNameListsBuiltinScenes) {
  const std::string msg = error_of([] { load_scene("no-such-scene-anywhere"); });
  EXPECT_NE(msg.find("no such scene or file: no-such-scene-anywhere (built-in scenes: "),
            std::string::npos)
      << msg;
  for (const BuiltinSceneInfo& b : builtin_scenes())
    EXPECT_NE(msg.find(b.name), std::string::npos) << msg;
}

TEST(LoadTest, MissingFileIsMissingFileError) {
  EXPECT_THROW(load_scene("/nonexistent/dir/scene.obj"), MissingFileError);
  EXPECT_THROW(load_scene("/nonexistent/dir/scene.json"), MissingFileError);
}

TEST(LoadTest, BuiltinSceneByName) {
  const std::vector<BuiltinSceneInfo> builtins = builtin_scenes();
  ASSERT_FALSE(builtins.empty());
  const Scene s = load_scene(builtins[0].name);
  EXPECT_FALSE(s.triangles.empty());
  EXPECT_EQ(s.normals.size(), s.positions.size());
}

TEST(LoadTest, DispatchesOnExtension) {
  TempDir dir;
  write_file(dir.path / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_file(dir.path / "scene.JSON",
             R"({"objects": [{"type": "mesh", "file": "tri.obj"}, {"type": "mesh", "file": "tri.obj"}]})");
  EXPECT_EQ(load_scene((dir.path / "tri.obj").string()).triangles.size(), 1u);
  EXPECT_EQ(load_scene((dir.path / "scene.JSON").string()).objects.size(), 2u);
}

TEST(LoadTest, NanVertexInObjIsRejected) {
  TempDir dir;
  const fs::path obj = dir.path / "nan.obj";
  write_file(obj, "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string msg = error_of([&] { load_scene(obj.string()); });
  EXPECT_NE(msg.find("nan.obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("non-finite"), std::string::npos) << msg;
}

TEST(LoadTest, InfVertexInObjIsRejected) {
  TempDir dir;
  const fs::path obj = dir.path / "inf.obj";
  write_file(obj, "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n");
  const std::string msg = error_of([&] { load_scene(obj.string()); });
  EXPECT_NE(msg.find("inf.obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("non-finite"), std::string::npos) << msg;
}

TEST(LoadTest, DegenerateTrianglesAreDroppedAndCounted) {
  TempDir dir;
  const fs::path obj = dir.path / "degen.obj";
  // Two good triangles and two of zero area (collinear corners, a repeated corner).
  write_file(obj, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                  "f 1 2 3\nf 1 3 4\nf 1 2 5\nf 1 1 3\n");
  const Scene s = load_scene(obj.string());
  EXPECT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.dropped_degenerate, 2u);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].triangle_count, 2u);
}

// Non-finite texture coordinates are replaced by sanitize_scene, so they never reach the
// texture lookup's float → int conversion.
TEST(LoadTest, NonFiniteUvsAreReplaced) {
  TempDir dir;
  const fs::path obj = dir.path / "uv.obj";
  write_file(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nvt 0 inf\nvt 0.5 0.5\nf 1/1 2/2 3/3\n");
  const Scene s = load_scene(obj.string());
  ASSERT_EQ(s.uvs.size(), 3u);
  int zeros = 0;
  for (const vec2& uv : s.uvs) {
    EXPECT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y));
    zeros += uv == vec2(0.0f);
  }
  EXPECT_EQ(zeros, 2);
}

TEST(LoadTest, MalformedFilesNameTheFile) {
  TempDir dir;
  write_file(dir.path / "broken.json", "{ \"objects\": ");
  write_file(dir.path / "broken.obj", "v 0 0 0\nf 1 2 7\n");
  for (const char* name : {"broken.json", "broken.obj"}) {
    const std::string msg = error_of([&] { load_scene((dir.path / name).string()); });
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace proxima
