#include "proxima/scene/import.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <vector>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/limits.h"
#include "proxima/core/image_io.h"
#include "test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? k[v & 63] : '=';
  }
  return out;
}

template <typename T>
void append_bytes(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// One triangle (0,0,0) (1,0,0) (0,1,0) as glTF 2.0 with an embedded base64 buffer, under a
// node with the given JSON fields, and one metallic/roughness material.
std::string tiny_gltf(const std::string& node_fields) {
  std::string buffer;
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append_bytes(buffer, f);
  for (uint16_t i : {0, 1, 2}) append_bytes(buffer, i);
  buffer.append(2, '\0');  // pad to 4 bytes
  return R"({
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "tri_node", "mesh": 0)" + node_fields + R"(}],
    "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
    "materials": [{"name": "metal",
                   "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.5, 0.2, 1],
                                            "metallicFactor": 0.75, "roughnessFactor": 0.25},
                   "emissiveFactor": [0.1, 0.2, 0.3]}],
    "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,)" +
         base64(buffer) + R"("}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
  })";
}

vec3 corner(const Scene& s, uint32_t triangle, int k) { return s.positions[s.triangles[triangle][k]]; }

// ASCII PLY header: 4 float vertices, `faces` faces with a uchar-counted index list.
std::string quad_ply_header(int faces) {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

TEST(ImportTest, ObjRoundTripKeepsGeometryAndMaterials) {
  TempDir dir;
  Scene scene;
  Material shiny;
  shiny.name = "shiny metal";  // a space: written as one OBJ token
  shiny.diffuse = vec3(0.2f, 0.4f, 0.6f);
  shiny.specular = 0.7f;
  shiny.gloss = 0.15f;
  Material lamp;
  lamp.name = "lamp";
  lamp.gloss = 1.0f;
  lamp.emission = vec3(2.0f, 1.5f, 1.0f);
  const uint32_t m0 = add_material(scene, shiny);
  const uint32_t m1 = add_material(scene, lamp);

  Mesh quad;
  quad.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  quad.triangles = {{0, 2, 1}, {0, 3, 2}};
  Mesh tetra;
  tetra.positions = {{0.125f, 1, 0.3f}, {1.5f, 1, 0.25f}, {0.5f, 2.75f, 0.5f}, {0.5f, 1.25f, 1.5f}};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  add_object(scene, quad, "floor", m0);
  add_object(scene, tetra, "tetra", m1);

  const fs::path obj = dir.path / "round.obj";
  write_obj(obj, scene);
  ASSERT_TRUE(fs::exists(dir.path / "round.mtl"));
  const Scene back = import_mesh_file(obj);

  ASSERT_EQ(back.triangles.size(), scene.triangles.size());
  ASSERT_EQ(back.objects.size(), 2u);
  EXPECT_EQ(back.objects[0].name, "floor");
  EXPECT_EQ(back.objects[1].name, "tetra");
  for (uint32_t t = 0; t < scene.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const vec3 d = glm::abs(corner(back, t, k) - corner(scene, t, k));
      EXPECT_LE(std::max({d.x, d.y, d.z}), 1e-5f) << "triangle " << t << " corner " << k;
    }
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const Material& want = scene.materials[scene.triangle_material[t]];
    const Material& got = back.materials[back.triangle_material[t]];
    EXPECT_NEAR(got.specular, want.specular, 1e-4f);
    EXPECT_NEAR(got.gloss, want.gloss, 1e-4f);
    EXPECT_NEAR(glm::distance(got.diffuse, want.diffuse), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(got.emission, want.emission), 0.0f, 1e-5f);
  }
  EXPECT_EQ(back.materials[back.triangle_material[0]].name, "shiny_metal");
}

TEST(ImportTest, HandWrittenObjWithMtlAndTexture) {
  TempDir dir;
  ImageF tex(2, 2, 3, 0.5f);
  write_png_linear(dir.path / "wood.png", tex);
  write_file(dir.path / "box.mtl", R"(# two materials
newmtl glossy
Kd 0.8 0.1 0.1
Ks 0.5 0.25 0.1
Ns 1000
Ke 0 0 0
newmtl rough
Kd 1 1 1
Ks 0 0 0
Ns 0
map_Kd wood.png
)");
  write_file(dir.path / "box.obj", R"(mtllib box.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
o quad
usemtl glossy
f 1/1 2/2 3/3 4/4
o tri
usemtl rough
f 1/1 2/2 5/3
)");
  const Scene s = import_mesh_file(dir.path / "box.obj");
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.triangles.size(), 3u);  // the quad is triangulated
  EXPECT_EQ(s.objects[0].triangle_count, 2u);

  const Material& glossy = s.materials[s.triangle_material[0]];
  EXPECT_EQ(glossy.name, "glossy");
  EXPECT_FLOAT_EQ(glossy.specular, 0.5f);  // max component of Ks
  EXPECT_NEAR(glossy.gloss, 0.0f, 1e-6f);  // Ns = 1000: the sharpest lobe
  EXPECT_EQ(glossy.diffuse_texture, -1);

  const Material& rough = s.materials[s.triangle_material[2]];
  EXPECT_EQ(rough.specular, 0.0f);
  EXPECT_NEAR(rough.gloss, 1.0f, 1e-6f);  // Ns = 0: the widest lobe
  ASSERT_GE(rough.diffuse_texture, 0);
  EXPECT_EQ(s.textures[size_t(rough.diffuse_texture)].image.width(), 2);
}

TEST(ImportTest, ObjWithMissingTextureFallsBackToColor) {
  TempDir dir;
  write_file(dir.path / "m.mtl", "newmtl a\nKd 0.3 0.3 0.3\nmap_Kd nowhere.png\n");
  write_file(dir.path / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  const Scene s = import_mesh_file(dir.path / "m.obj");
  EXPECT_EQ(s.materials[s.triangle_material[0]].diffuse_texture, -1);
  EXPECT_TRUE(s.textures.empty());
}

TEST(ImportTest, GltfMetallicRoughnessAndNodeTransform) {
  TempDir dir;
  write_file(dir.path / "tri.gltf", tiny_gltf(R"(, "translation": [0, 0, -2])"));
  const Scene s = import_mesh_file(dir.path / "tri.gltf");
  ASSERT_EQ(s.triangles.size(), 1u);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].name, "tri");
  for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(corner(s, 0, k).z, -2.0f);

  const Material& m = s.materials[s.triangle_material[0]];
  EXPECT_EQ(m.name, "metal");
  EXPECT_FLOAT_EQ(m.specular, 0.75f);
  EXPECT_FLOAT_EQ(m.gloss, 0.25f);
  EXPECT_NEAR(glm::distance(m.diffuse, vec3(0.9f, 0.5f, 0.2f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(m.emission, vec3(0.1f, 0.2f, 0.3f)), 0.0f, 1e-6f);
}

TEST(ImportTest, GltfMirroringNodeKeepsOutwardWinding) {
  TempDir dir;
  write_file(dir.path / "mirror.gltf", tiny_gltf(R"(, "scale": [-1, 1, 1])"));
  const Scene s = import_mesh_file(dir.path / "mirror.gltf");
  ASSERT_EQ(s.triangles.size(), 1u);
  // The source triangle faces +Z; mirroring in X must not turn it to face −Z.
  const vec3 n = glm::cross(corner(s, 0, 1) - corner(s, 0, 0), corner(s, 0, 2) - corner(s, 0, 0));
  EXPECT_GT(n.z, 0.0f);
  EXPECT_EQ(scene_bounds(s).min.x, -1.0f);
}

TEST(ImportTest, AsciiPly) {
  TempDir dir;
  write_file(dir.path / "quad.ply", R"(ply
format ascii 1.0
element vertex 5
property float x
property float y
property float z
element face 2
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
4 0 1 2 3
3 0 4 1
)");
  const Scene s = import_mesh_file(dir.path / "quad.ply");
  EXPECT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.normals.size(), s.positions.size());  // generated: PLY had none
}

TEST(ImportTest, MissingFileNamesIt) {
  TempDir dir;
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "absent.obj"); });
  EXPECT_NE(msg.find("absent.obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
}

TEST(ImportTest, MalformedObjNamesFile) {
  TempDir dir;
  write_file(dir.path / "bad.obj", "v 0 0 0\nf 1 2 3\n");  // faces index missing vertices
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "bad.obj"); });
  EXPECT_NE(msg.find("bad.obj"), std::string::npos) << msg;
}

TEST(ImportTest, MalformedGltfNamesFile) {
  TempDir dir;
  write_file(dir.path / "bad.gltf", R"({"asset": {"version": "2.0"}, "meshes": [)");
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "bad.gltf"); });
  EXPECT_NE(msg.find("bad.gltf"), std::string::npos) << msg;
}

TEST(ImportTest, LinesOnlyHaveNoTriangles) {
  TempDir dir;
  write_file(dir.path / "lines.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\n");
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "lines.obj"); });
  EXPECT_NE(msg.find("lines.obj: no triangles"), std::string::npos) << msg;
}

// A glTF whose nodes form a chain `depth` deep, the last one holding a triangle.
std::string deep_gltf(int depth) {
  std::string nodes;
  for (int i = 0; i < depth; ++i) {
    if (i) nodes += ",";
    nodes += i + 1 < depth ? R"({"children": [)" + std::to_string(i + 1) + R"(], "translation": [1, 0, 0]})"
                           : std::string(R"({"mesh": 0})");
  }
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [)" + nodes +
         R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
         "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
         "bufferViews": [{"buffer": 0, "byteLength": 36}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                        "min": [0, 0, 0], "max": [1, 1, 0]}]})";
}

// A glTF node chain 100000 deep would overflow the stack inside assimp's recursive node
// building. Graphs up to kMaxNodeDepth levels load, every level's
// transform applied; deeper ones are refused before assimp recurses into them.
TEST(ImportTest, DeepNodeGraphLoadsWithoutStackOverflow) {
  TempDir dir;
  write_file(dir.path / "deep.gltf", deep_gltf(kMaxNodeDepth));
  const Scene s = import_mesh_file(dir.path / "deep.gltf");
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_FLOAT_EQ(s.positions[0].x, float(kMaxNodeDepth - 1));  // depth − 1 translations of +1 in x
  for (int depth : {kMaxNodeDepth + 1, 100000}) {
    write_file(dir.path / "deeper.gltf", deep_gltf(depth));
    const std::string msg = error_of([&] { import_mesh_file(dir.path / "deeper.gltf"); });
    EXPECT_NE(msg.find("deeper.gltf: glTF node graph is more than 1000 levels deep"), std::string::npos) << msg;
  }
}

// assimp's glTF reader (rapidjson) recurses per JSON nesting level, and its
// node builder follows cycles forever; both are refused before assimp reads the file.
TEST(ImportTest, DeepJsonNestingAndNodeCyclesAreRefusedBeforeAssimp) {
  TempDir dir;
  const std::string deep = R"({"asset": {"version": "2.0"}, "extras": )" + std::string(200000, '[') +
                           std::string(200000, ']') + "}";
  write_file(dir.path / "nested.gltf", deep);
  std::string msg = error_of([&] { import_mesh_file(dir.path / "nested.gltf"); });
  EXPECT_NE(msg.find("nested.gltf: JSON nested more than 256 levels deep"), std::string::npos) << msg;
  // The same JSON in a GLB's JSON chunk.
  std::string glb = "glTF" + std::string("\x02\0\0\0", 4) + std::string(4, '\0');
  const uint32_t n = uint32_t(deep.size());
  glb += std::string{char(n & 255), char(n >> 8 & 255), char(n >> 16 & 255), char(n >> 24)} + "JSON" + deep;
  write_file(dir.path / "nested.glb", glb);
  msg = error_of([&] { import_mesh_file(dir.path / "nested.glb"); });
  EXPECT_NE(msg.find("nested.glb: JSON nested more than 256 levels deep"), std::string::npos) << msg;
  // A cycle (0 → 1 → 0) and a node with two parents.
  std::string cycle = deep_gltf(3);
  cycle.replace(cycle.find(R"({"mesh": 0})"), 11, R"({"mesh": 0, "children": [0]})");
  write_file(dir.path / "cycle.gltf", cycle);
  msg = error_of([&] { import_mesh_file(dir.path / "cycle.gltf"); });
  EXPECT_NE(msg.find("cycle.gltf: glTF node graph "), std::string::npos) << msg;
  std::string shared = deep_gltf(3);
  shared.replace(shared.find(R"({"children": [1])"), 16, R"({"children": [1, 2])");
  write_file(dir.path / "shared.gltf", shared);
  msg = error_of([&] { import_mesh_file(dir.path / "shared.gltf"); });
  EXPECT_NE(msg.find("shared.gltf: glTF node graph is not a tree: node 2 has two parents"), std::string::npos) << msg;
}

// Only the tested and fuzzed importers (OBJ, PLY, glTF 2.0) are used; a
// Collada file is refused by its extension, and by content when it hides behind `.obj`.
TEST(ImportTest, UntestedFormatsAreRefused) {
  TempDir dir;
  const std::string dae = R"(<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1"><asset/></COLLADA>)";
  write_file(dir.path / "model.dae", dae);
  std::string msg = error_of([&] { import_mesh_file(dir.path / "model.dae"); });
  EXPECT_NE(msg.find("model.dae: unsupported mesh format '.dae'"), std::string::npos) << msg;
  write_file(dir.path / "disguised.obj", dae);
  msg = error_of([&] { import_mesh_file(dir.path / "disguised.obj"); });
  EXPECT_NE(msg.find("disguised.obj: "), std::string::npos) << msg;
}

// assimp loops forever on a PLY header whose `end_header` line is misspelled, or with NUL
// bytes in a line.
TEST(ImportTest, MalformedPlyHeaderIsAnErrorNotAHang) {
  TempDir dir;
  write_file(dir.path / "open.ply",
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_head0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "open.ply"); });
  EXPECT_NE(msg.find("open.ply: PLY header has an unknown line 'end_head0 0 0'"), std::string::npos) << msg;
  // …and on NUL bytes before end_header.
  write_file(dir.path / "nul.ply", std::string("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\0\0end_header\n", 68));
  const std::string nul = error_of([&] { import_mesh_file(dir.path / "nul.ply"); });
  EXPECT_NE(nul.find("nul.ply: PLY header line 5 is not ASCII text"), std::string::npos) << nul;
  // …and when the magic is in another case (assimp matches "plY" too).
  write_file(dir.path / "upper.ply", "plY\nformat ascii 1. vertex 4\nproperty float x\nproperty ");
  const std::string upper = error_of([&] { import_mesh_file(dir.path / "upper.ply"); });
  EXPECT_NE(upper.find("upper.ply: PLY header has an unknown format line 'format ascii 1. vertex 4'"), std::string::npos)
      << upper;
  // A well-formed header with comments and CRLF line ends still loads.
  write_file(dir.path / "crlf.ply",
             "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nelement vertex 3\r\nproperty float x\r\n"
             "property float y\r\nproperty float z\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\n"
             "end_header\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n");
  EXPECT_EQ(import_mesh_file(dir.path / "crlf.ply").triangles.size(), 1u);
}

// A garbled face list trips an internal assertion in assimp's triangulation, which calls
// abort(); the interposed aiAssertViolation turns it into an error, and the cause (a face
// the PLY reader leaves without indices, as in
// PlyFacesWithoutIndicesAreAnErrorNotAPostProcessingCrash) is refused before any
// post-processing step runs.
TEST(ImportTest, PlyTrippingAnAssimpAssertionIsAnError) {
  TempDir dir;
  write_file(dir.path / "garbled.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
             "3 0 1 2\nat x\nproperty float y\np3 0 2 3\n");
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "garbled.ply"); });
  // The body is checked against the header before assimp reads it.
  EXPECT_NE(msg.find("garbled.ply: PLY body line 6 has 'at' where an integer"), std::string::npos) << msg;
}

// assimp's PLY reader loops forever (fread in a loop) on a `.ply` starting with an empty
// line and naming a garbled format.
TEST(ImportTest, PlyWithoutLeadingMagicOrWithUnknownFormatIsAnErrorNotAHang) {
  TempDir dir;
  write_file(dir.path / "lead.ply",
             "\nply\nformat binary_lend_heaneran 1.0\nelement vertran 1.0\nelement vertex 3\nproperty float x @p\n"
             "property float y\nproperty flo");
  std::string msg = error_of([&] { import_mesh_file(dir.path / "lead.ply"); });
  EXPECT_NE(msg.find("lead.ply: PLY header does not start with the line 'ply'"), std::string::npos) << msg;
  write_file(dir.path / "format.ply",
             "ply\nformat binary_lend_heaneran 1.0\nelement vertex 3\nproperty float x\nend_header\n");
  msg = error_of([&] { import_mesh_file(dir.path / "format.ply"); });
  EXPECT_NE(msg.find("format.ply: PLY header has an unknown format line 'format binary_lend_heaneran 1.0'"),
            std::string::npos)
      << msg;
  write_file(dir.path / "noformat.ply", "ply\nelement vertex 3\nproperty float x\nend_header\n");
  msg = error_of([&] { import_mesh_file(dir.path / "noformat.ply"); });
  EXPECT_NE(msg.find("noformat.ply: PLY header has no valid format line"), std::string::npos) << msg;
}

// `end_headeR` fails assimp's exact keyword match, so assimp would parse the binary body as
// header (SEGV): keywords are matched exactly, in one case.
TEST(ImportTest, PlyHeaderKeywordInAnotherCaseIsAnErrorNotACrash) {
  TempDir dir;
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_headeR\n";
  ply += std::string("\0\0\0\0\0\0\0\0\0pply\n\x01\x0b?\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80?\0\0\0\xfb\x02\0\0\0\0\x01\0\0\0\x02\0\0\0", 48);
  write_file(dir.path / "case.ply", ply);
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "case.ply"); });
  EXPECT_NE(msg.find("case.ply: PLY header has an unknown line 'end_headeR'"), std::string::npos) << msg;
}

// A malformed property line `property float(y` is refused before assimp reads the file.
TEST(ImportTest, PlyMalformedPropertyLineIsAnError) {
  TempDir dir;
  write_file(dir.path / "prop.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float(y\nproperty float z\n"
             "element face 6\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 \n");
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "prop.ply"); });
  EXPECT_NE(msg.find("prop.ply: PLY header has a malformed property line 'property float(y'"), std::string::npos) << msg;
}


// assimp's PLY reader reserves what the file declares before reading it. An ASCII face
// list counting 3111…1 entries (wrapped to 3,340,530,119 entries of 8 bytes) makes it
// request 26.7 GB (ASan: out of memory; a bad_alloc or worse without
// it). Declared element counts must fit in the bytes after end_header, and ASCII list
// counts in their line.
TEST(ImportTest, PlyCountsLargerThanTheFileAreRefusedBeforeAllocating) {
  TempDir dir;
  const std::string header = quad_ply_header(2);
  write_file(dir.path / "list.ply",
             header + "0 0 0\n1 0 0\n1  10\n0 1 0\n3" + std::string(67, '1') + " 0 1 2\n3 0 1 2\n");
  std::string msg = error_of([&] { import_mesh_file(dir.path / "list.ply"); });
  // The body walk stops at the first line that does not match the header.
  EXPECT_NE(msg.find("list.ply: PLY body line 3 has fewer values than its 'vertex' element declares"), std::string::npos)
      << msg;
  write_file(dir.path / "list5.ply", header + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3" + std::string(67, '1') + " 0 1 2\n3 0 1 2\n");
  msg = error_of([&] { import_mesh_file(dir.path / "list5.ply"); });
  EXPECT_NE(msg.find("list5.ply: PLY body line 5 has '31111111111111111111' where an integer in the range of its type"),
            std::string::npos)
      << msg;
  write_file(dir.path / "long.ply", header + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4000000000 0 1 2\n3 0 1 2\n");
  msg = error_of([&] { import_mesh_file(dir.path / "long.ply"); });
  EXPECT_NE(msg.find("long.ply: PLY body line 5 has '4000000000' where an integer in the range of its type"),
            std::string::npos)
      << msg;
  // assimp re-reads the last full line for every instance the body lacks (the last line has
  // no newline, so it is not delivered): the faces all read the `2222…` line (ply_fuzz: 19 GB).
  write_file(dir.path / "reread.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float z\nelement face 8\n"
             "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 mw1St5ctypeIcE3 0 1 2\n" +
                 std::string(120, '2') + " 0 2 3\n" + std::string(56, ' '));
  msg = error_of([&] { import_mesh_file(dir.path / "reread.ply"); });
  EXPECT_NE(msg.find("reread.ply: PLY body line 1 has more values than its 'vertex' element declares"), std::string::npos)
      << msg;
  // Element counts against the file size, ASCII and binary (12 bytes per float vertex).
  std::string many = header;
  many.replace(many.find("vertex 4"), 8, "vertex 2000000000");
  write_file(dir.path / "many.ply", many + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  msg = error_of([&] { import_mesh_file(dir.path / "many.ply"); });
  EXPECT_NE(msg.find("many.ply: PLY header declares 2000000000 'vertex' elements, more than the 40 bytes after end_header can hold"),
            std::string::npos)
      << msg;
  write_file(dir.path / "binary.ply",
             "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
             "property float z\nend_header\n" + std::string(23, '\0'));
  msg = error_of([&] { import_mesh_file(dir.path / "binary.ply"); });
  EXPECT_NE(msg.find("binary.ply: PLY header declares 2 'vertex' elements, more than the 23 bytes"), std::string::npos) << msg;
  // The same files with honest counts load.
  write_file(dir.path / "honest.ply", header + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  EXPECT_EQ(import_mesh_file(dir.path / "honest.ply").triangles.size(), 2u);
  write_file(dir.path / "no_newline.ply", header + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3");
  EXPECT_EQ(import_mesh_file(dir.path / "no_newline.ply").triangles.size(), 2u);
}

// A BUS crash inside assimp 5.2.5's SortByPType step. The PLY reader allocates the declared
// `element face N` faces up front and, on this garbled body (a face line running into the
// next, then a second header), fills only two of them; the rest keep zero indices.
// ValidateDataStructure skips face checks while the mesh's primitive types are unset (the
// PLY reader leaves them 0), the preprocessor then counts the empty faces as polygons, and
// SortByPType (the only step that crashes on its own on this input) reads through a garbage
// pointer. proxima reads without post-processing, checks every face, and only then runs the
// steps.
TEST(ImportTest, PlyFacesWithoutIndicesAreAnErrorNotAPostProcessingCrash) {
  TempDir dir;
  // A garbled body, then the header's last lines and a body again.
  write_file(dir.path / "empty_faces.ply",
             quad_ply_header(4) + "0 0 0\n1 0 0\n1 1 0\n0 1 01 0\n3 02\n2z\n" +
                 quad_ply_header(4).substr(quad_ply_header(4).find("element face")) +
                 "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n2 0 0 2 3\n");
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "empty_faces.ply"); });
  // Refused by the body walk, before assimp reads the file; the check after assimp's read
  // is a second net.
  EXPECT_NE(msg.find("empty_faces.ply: PLY body line 4 has more values than its 'vertex' element declares"),
            std::string::npos)
      << msg;
}

// A binary PLY of `vertices` float vertices (0, 0, 0), (1, 0, 0), … and faces given as
// raw bytes (each a count and indices, in the header's list types).
std::string binary_ply(const std::string& format, int vertices, int faces, const std::string& list_types,
                       const std::string& face_bytes) {
  std::string ply = "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
                    "\nproperty list " + list_types + " vertex_indices\nend_header\n";
  const bool big = format == "binary_big_endian";
  for (int v = 0; v < vertices; ++v)
    for (int axis = 0; axis < 3; ++axis) {
      const float f = axis == 0 ? float(v % 2) : axis == 1 ? float(v / 2) : 0.0f;
      uint32_t u = 0;
      std::memcpy(&u, &f, 4);
      for (int b = 0; b < 4; ++b) ply += char(uint8_t(u >> (big ? 8 * (3 - b) : 8 * b)));
    }
  return ply + face_bytes;
}
std::string le32(int32_t v) {
  std::string s;
  for (int b = 0; b < 4; ++b) s += char(uint8_t(uint32_t(v) >> (8 * b)));
  return s;
}

// Out of memory in assimp's PLY reader (1.3 GB, then 2.6 GB; the input is
// fuzz/regressions/ply/ply-oom-8250f791.ply). assimp parses the count of an element it does
// not know (`element ~ertex 4`) from the name itself, i.e. 0, so the first vertex line
// `777…770 0 0` becomes the first face and its first number the face's list count,
// 164,043,882 after wrapping; assimp reserves that many 8-byte values, then doubles them.
// So elements assimp does not read must come after the ones it reads, and the body is
// checked value by value against the header before assimp opens the file.
TEST(ImportTest, PlyUnknownElementBeforeTheGeometryIsRefusedNotMisreadAsAHugeList) {
  TempDir dir;
  // The input (294 bytes).
  const std::string found =
      std::string("ply\nformat ascii 1.0\nelement ~ertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 8\nproperty list uchar int vertex_indice:\nend_header\n777777777777777777777777770 0 0\n"
                  "1 0 0\n1 1 0\n0 1 0\n3 0 element face 8\nproper") +
      std::string(10, '\0') + " 3\n" + std::string(15, '\x99') + "_indice:\nend_" + std::string(11, '\0') + "0\n1" +
      "\x89\x99\x89" + std::string(7, '\x99');
  ASSERT_EQ(found.size(), 294u);
  write_file(dir.path / "ply-oom-8250f791.ply", found);
  std::string msg = error_of([&] { import_mesh_file(dir.path / "ply-oom-8250f791.ply"); });
  EXPECT_NE(msg.find("ply-oom-8250f791.ply: PLY header has '~ertex' elements before the 'face' ones"), std::string::npos)
      << msg;
  // A well-formed file with an extra element: refused before the geometry (assimp would
  // take the camera line for vertex 0), loaded after it.
  const std::string camera = "element camera 1\nproperty float fov\n";
  std::string before = quad_ply_header(2);
  before.insert(before.find("element vertex"), camera);
  write_file(dir.path / "before.ply", before + "45\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  msg = error_of([&] { import_mesh_file(dir.path / "before.ply"); });
  EXPECT_NE(msg.find("before.ply: PLY header has 'camera' elements before the 'vertex' ones"), std::string::npos) << msg;
  std::string after = quad_ply_header(2);
  after.insert(after.find("end_header"), camera);
  write_file(dir.path / "after.ply", after + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n45\n");
  EXPECT_EQ(import_mesh_file(dir.path / "after.ply").triangles.size(), 2u);
  // A name starting with digits: assimp would read them as its count.
  std::string digits = quad_ply_header(2);
  digits.insert(digits.find("end_header"), "element 4294967295x 0\nproperty float a\n");
  write_file(dir.path / "digits.ply", digits + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  msg = error_of([&] { import_mesh_file(dir.path / "digits.ply"); });
  EXPECT_NE(msg.find("digits.ply: PLY header has an element name starting with a digit"), std::string::npos) << msg;
}

// The ASCII body is read value by value as the header declares
// it, so what assimp reads is what proxima checked (counts, list lengths, indices).
TEST(ImportTest, PlyAsciiBodyNotMatchingItsHeaderIsRefused) {
  TempDir dir;
  const std::string header = quad_ply_header(2);
  const std::string vertices = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {vertices + "3 0 1 2 7\n3 0 2 3\n", "PLY body line 5 has more values than its 'face' element declares"},
      {vertices + "3 0 1\n3 0 2 3\n", "PLY body line 5 has fewer values than its 'face' element declares"},
      {"0 0 0\n1 0 x\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n", "PLY body line 2 has 'x' where a number"},
      {vertices + "300 0 1 2\n3 0 2 3\n", "PLY body line 5 has '300' where an integer in the range of its type"},
      {vertices + "3 0 1 4\n3 0 2 3\n", "PLY body line 5 has vertex index 4 out of range (4 vertices)"},
      {vertices + "3 0 -1 2\n3 0 2 3\n", "PLY body line 5 has vertex index -1 out of range"},
      {vertices + "0\n3 0 2 3\n", "PLY body line 5 has a 'face' without vertex indices"},
      {vertices + "3 0 1 2\n", "PLY body line 6 is missing: the header declares 2 'face' elements"},
      {vertices + "3 0 1 2\n3 0 2 3\n0 0 0\n", "PLY body line 7 follows the last element"},
      {vertices + "3 0 1 2\n\n3 0 2 3\n", "PLY body line 6 is empty"},
      {vertices + "3 0 1 2\n3 0 2 3" + std::string(1, '\0') + "\n", "PLY body line 6 is not ASCII text"},
  };
  for (const auto& [body, expected] : cases) {
    write_file(dir.path / "bad.ply", header + body);
    const std::string msg = error_of([&] { import_mesh_file(dir.path / "bad.ply"); });
    EXPECT_NE(msg.find("bad.ply: " + expected), std::string::npos) << msg;
  }
  // Signs, exponents, tabs, CR LF and trailing blank lines are fine.
  write_file(dir.path / "good.ply", header + "-0.0 +0 0\n1e0 0 0\r\n1 1.0 0\n\t0 1 0E+0 \n3 0 1 2\n3 0 2 3\n\n \n");
  EXPECT_EQ(import_mesh_file(dir.path / "good.ply").triangles.size(), 2u);
}

// assimp reads binary list counts unchecked (a face count of 2·10^9 int entries would
// reserve 16 GB), so proxima reads each count before assimp runs: non-negative, within the
// bytes left, a face at most kMaxFaceVertices long, and its indices in range.
TEST(ImportTest, PlyBinaryListCountsAreCheckedBeforeAssimpReads) {
  TempDir dir;
  auto face = [](int n, std::vector<int> indices) {
    std::string s = le32(n);
    for (int i : indices) s += le32(i);
    return s;
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {binary_ply("binary_little_endian", 4, 1, "int int", face(2000000000, {0, 1, 2})),
       "PLY body, 'face' 0: a 'face' of 2000000000 vertices, more than 1024"},
      {binary_ply("binary_little_endian", 4, 1, "int int", face(-5, {0, 1, 2})), "PLY body, 'face' 0: a list count of -5"},
      {binary_ply("binary_little_endian", 4, 2, "int int", face(3, {0, 1, 2}) + face(4, {0, 1, 2})),
       "PLY body, 'face' 1: a list of 4 entries, more than the 12 bytes left hold"},
      {binary_ply("binary_little_endian", 4, 1, "int int", face(3, {0, 1, 9})),
       "PLY body, 'face' 0: vertex index 9 out of range (4 vertices)"},
      {binary_ply("binary_little_endian", 4, 2, "int int", face(3, {0, 1, 2}) + face(0, {})),
       "PLY body, 'face' 1: a 'face' without vertex indices"},
      {binary_ply("binary_little_endian", 4, 1, "int int", "").substr(0, 200),
       "PLY header declares 4 'vertex' elements, more than the"},
  };
  for (const auto& [ply, expected] : cases) {
    write_file(dir.path / "bad.ply", ply);
    const std::string msg = error_of([&] { import_mesh_file(dir.path / "bad.ply"); });
    EXPECT_NE(msg.find("bad.ply: " + expected), std::string::npos) << msg;
  }
  // A list that is not a face's: its count checked against the bytes left too.
  std::string texcoords = binary_ply("binary_little_endian", 4, 1, "uchar int", std::string("\x03", 1) + le32(0) + le32(1) + le32(2));
  texcoords.insert(texcoords.find("end_header"), "element edge 1\nproperty list int float weights\n");
  write_file(dir.path / "weights.ply", texcoords + le32(1 << 30) + le32(0));
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "weights.ply"); });
  EXPECT_NE(msg.find("weights.ply: PLY body, 'edge' 0: a list of 1073741824 entries, more than the 4 bytes left hold"),
            std::string::npos)
      << msg;
  // Honest files load, in either byte order.
  write_file(dir.path / "le.ply", binary_ply("binary_little_endian", 4, 2, "int int", face(3, {0, 1, 2}) + face(3, {1, 3, 2})));
  EXPECT_EQ(import_mesh_file(dir.path / "le.ply").triangles.size(), 2u);
  write_file(dir.path / "be.ply", binary_ply("binary_big_endian", 4, 1, "uchar ushort", std::string("\x04\0\0\0\x01\0\x03\0\x02", 9)));
  EXPECT_EQ(import_mesh_file(dir.path / "be.ply").triangles.size(), 2u);
}

// assimp triangulates an n-gon by ear clipping, superlinear in n (a 4096-gon takes 1.4 s),
// so a few huge faces would hang an import. Faces above kMaxFaceVertices are refused before
// triangulation, for every format.
TEST(ImportTest, FaceWithMoreThanMaxFaceVerticesIsRefusedBeforeTriangulation) {
  TempDir dir;
  const int n = kMaxFaceVertices + 1;
  std::string obj, f = "f";
  for (int i = 0; i < n; ++i) {
    obj += "v ";
    obj += std::to_string(1000 * std::cos(6.2831853 * i / n));
    obj += ' ';
    obj += std::to_string(1000 * std::sin(6.2831853 * i / n));
    obj += " 0\n";
    f += ' ';
    f += std::to_string(i + 1);
  }
  write_file(dir.path / "ngon.obj", obj + f + "\n");
  const std::string msg = error_of([&] { import_mesh_file(dir.path / "ngon.obj"); });
  EXPECT_NE(msg.find("ngon.obj: mesh 0: face 0 has 1025 vertices, more than 1024"), std::string::npos) << msg;
  // One vertex fewer is a face like any other.
  write_file(dir.path / "ok.obj", obj + f.substr(0, f.rfind(' ')) + "\n");
  EXPECT_EQ(import_mesh_file(dir.path / "ok.obj").triangles.size(), size_t(kMaxFaceVertices - 2));
}

TEST(ImportTest, WriteObjIntoMissingDirectoryLeavesNothing) {
  TempDir dir;
  Scene scene;
  Mesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.triangles = {{0, 1, 2}};
  add_object(scene, tri, "t", add_material(scene, Material{}));
  EXPECT_THROW(write_obj(dir.path / "no" / "such" / "dir.obj", scene), InputError);
  EXPECT_FALSE(fs::exists(dir.path / "no"));
}

}  // namespace

// Input obj-leak-01497ee4 (fuzz/regressions/obj/): `f 07` refers to vertex 7 where assimp
// reads 6 (it drops `v 0 1\x1f0`, two components). assimp checks face indices only while
// building the mesh, and its "OBJ: vertex index out of range" exception leaks that mesh
// (1,392 bytes). proxima checks OBJ indices before assimp opens the file.
TEST(ImportTest, ObjFaceIndexOutOfRangeIsRefusedBeforeAssimpCanLeakItsMesh) {
  TempDir dir;
  static const char kFound[] =
      "g a\nv 5 0 0\nv 1 0 0\nv 0 1\x1f"
      "0\nv 0 0 1\nf 1 2 3\no qf -\x14 -2 -1\ng b\x01\x00\x00\x00\n]g 2 3 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 07\nl 1 2\n";
  const std::string found(kFound, sizeof(kFound) - 1);
  ASSERT_EQ(found.size(), 110u);
  write_file(dir.path / "obj-leak-01497ee4.obj", found);
  std::string msg = error_of([&] { import_mesh_file(dir.path / "obj-leak-01497ee4.obj"); });
  EXPECT_NE(msg.find("obj-leak-01497ee4.obj: line 13: OBJ vertex index 7 out of range (the file has 6)"),
            std::string::npos)
      << msg;

  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n";
  const struct {
    std::string body, message;  // message empty: loads
  } cases[] = {
      {quad + "f 1 2 3\nf -4 -2 -1\n", ""},                    // relative indices
      {quad + "f 1//1 2//1 3//1 4//1\n", ""},                  // normals in range
      {quad + "f 1/9 2/9 3/9\n", ""},                          // no `vt`: assimp ignores them
      {quad + "f 1 2 5\n", "line 6: OBJ vertex index 5 out of range (the file has 4)"},
      {quad + "f 0 1 2\n", "line 6: OBJ vertex index 0"},
      {quad + "f -5 1 2\n", "line 6: OBJ vertex index refers before the first vertex"},
      {quad + "f 1//2 2//1 3//1\n", "line 6: OBJ normal index 2 out of range (the file has 1)"},
      {quad + "f 1 2 3\nl 1 9\n", "line 7: OBJ vertex index 9 out of range"},
  };
  for (size_t i = 0; i < std::size(cases); ++i) {
    const fs::path file = dir.path / ("case" + std::to_string(i) + ".obj");
    write_file(file, cases[i].body);
    if (cases[i].message.empty()) {
      EXPECT_GE(import_mesh_file(file).triangles.size(), 1u) << cases[i].body;
    } else {
      msg = error_of([&] { import_mesh_file(file); });
      EXPECT_NE(msg.find(file.string() + ": " + cases[i].message), std::string::npos) << cases[i].body << "\n" << msg;
    }
  }
}

}  // namespace proxima
