// Resource limits: oversized scenes, instancing and images fail with a message naming the
// file, the size and the flag, before anything large is allocated.
#include "proxima/core/limits.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/scene/load.h"
#include "test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

// Sets limits for one test and restores the previous ones.
struct ScopedLimits {
  Limits saved = limits();
  explicit ScopedLimits(Limits l) { set_limits(l); }
  ~ScopedLimits() { set_limits(saved); }
};

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(Limits, DefaultsAreResolved) {
  const Limits l = limits();
  EXPECT_GT(l.max_triangles, 0u);
  EXPECT_GT(l.max_memory_mb, 0u);  // 0 in Limits means "¾ of RAM", never returned
  EXPECT_EQ(geometry_bytes(2, 3), 2 * geometry_bytes(1, 0) + 3 * geometry_bytes(0, 1));
}

TEST(Limits, SceneFileTriangleLimitNamesObjectCountAndFlag) {
  ScopedLimits scoped({.max_triangles = 1000, .max_memory_mb = 0});
  TempDir dir;
  write_file(dir.path / "big.json",
             R"({"objects": [{"type": "box", "size": [1, 1, 1]}, {"type": "sphere", "radius": 1, "segments": 64, "rings": 64}]})");
  const std::string msg = error_of([&] { load_scene((dir.path / "big.json").string()); });
  EXPECT_TRUE(contains(msg, "big.json: objects[1]: 8076 triangles exceed the limit of 1000 (--max-triangles"))
      << msg;  // 12 box + 2·64·63 sphere triangles
}

TEST(Limits, SceneFileMemoryEstimateIsCheckedBeforeGenerating) {
  // 4096 × 4096 segments would be 33M triangles (several GB); the check comes first.
  ScopedLimits scoped({.max_triangles = 100'000'000, .max_memory_mb = 64});
  TempDir dir;
  write_file(dir.path / "huge.json", R"({"objects": [{"type": "torus", "major_radius": 1, "minor_radius": 0.5,
             "major_segments": 4096, "minor_segments": 4096}]})");
  const std::string msg = error_of([&] { load_scene((dir.path / "huge.json").string()); });
  EXPECT_TRUE(contains(msg, "huge.json: objects[0]: 33554432 triangles")) << msg;
  EXPECT_TRUE(contains(msg, "more than the limit of 64 MiB (--max-memory-mb")) << msg;
}

TEST(Limits, BuiltinScenesAreHeldToTheLimit) {
  ScopedLimits scoped({.max_triangles = 10, .max_memory_mb = 0});
  const std::string msg = error_of([] { load_scene("cornell"); });
  EXPECT_TRUE(contains(msg, "cornell: ")) << msg;
  EXPECT_TRUE(contains(msg, "exceed the limit of 10")) << msg;
}

// One mesh instanced by many nodes: the flattened count is what is checked.
TEST(Limits, GltfInstancingCountsEveryInstance) {
  ScopedLimits scoped({.max_triangles = 100, .max_memory_mb = 0});
  TempDir dir;
  // A triangle (3 float positions) instanced by 64 nodes: 64 triangles; then by 128: 128.
  const std::string buffer = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
  auto gltf = [&](int nodes) {
    std::string list, refs;
    for (int i = 0; i < nodes; ++i) {
      list += std::string(i ? "," : "") + R"({"mesh": 0, "translation": [)" + std::to_string(i) + ", 0, 0]}";
      refs += std::string(i ? "," : "") + std::to_string(i);
    }
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [)" + refs + R"(]}], "nodes": [)" + list +
           R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
           "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" + buffer + R"("}],
           "bufferViews": [{"buffer": 0, "byteLength": 36}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 1, 0]}]})";
  };
  write_file(dir.path / "fits.gltf", gltf(64));
  EXPECT_EQ(load_scene((dir.path / "fits.gltf").string()).triangles.size(), 64u);
  write_file(dir.path / "instanced.gltf", gltf(128));
  const std::string msg = error_of([&] { load_scene((dir.path / "instanced.gltf").string()); });
  EXPECT_TRUE(contains(msg, "instanced.gltf: 128 triangles exceed the limit of 100")) << msg;
}

// A PNG whose header claims 20000 × 10 pixels: rejected from the header, before decoding.
TEST(Limits, PngHeaderOverMaxSideIsRejectedBeforeDecoding) {
  TempDir dir;
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\0\0\0\x0dIHDR", 8);
  png += std::string("\0\0\x4e\x20\0\0\0\x0a\x08\x02\0\0\0", 13);  // 20000 × 10, 8-bit RGB
  png += std::string("\0\0\0\0", 4);                                 // CRC (stb ignores it)
  write_file(dir.path / "wide.png", png);
  const std::string msg = error_of([&] { read_image_linear(dir.path / "wide.png"); });
  EXPECT_TRUE(contains(msg, "wide.png: image of 20000x10 pixels exceeds the maximum side 16384")) << msg;
}

TEST(Limits, ExrOverTheMemoryLimitIsRejectedBeforeDecoding) {
  TempDir dir;
  write_exr(dir.path / "big.exr", ImageF(1024, 512, 3, 0.5f));  // 6 MiB as floats
  EXPECT_EQ(read_exr(dir.path / "big.exr").width(), 1024);
  ScopedLimits scoped({.max_triangles = 1000, .max_memory_mb = 4});
  const std::string msg = error_of([&] { read_exr(dir.path / "big.exr"); });
  EXPECT_TRUE(contains(msg, "big.exr: image of 1024x512 pixels needs about 6 MiB, more than the limit of 4 MiB"))
      << msg;
}

}  // namespace
}  // namespace proxima
