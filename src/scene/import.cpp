// Mesh-file import through assimp and Wavefront OBJ export.
// assimp stays inside this file (STYLE.md: libraries wrapped in one file each). Its
// default logger is the NullLogger, so nothing reaches stdout; its errors come back
// through Importer::GetErrorString() and are turned into InputError here.
//
// Material mapping (docs/formats.md):
//   glTF metallic/roughness:  s = metallic, g = roughness.
//   OBJ / MTL Ks, Ns:         s = max(Ks.r, Ks.g, Ks.b),
//                             g = clamp(1 − log(Ns + 1) / log(1001), 0, 1),
//   inverted by write_obj as  Ks = (s, s, s), Ns = 1001^(1 − g) − 1 (Ns in [0, 1000]).
#include "proxima/scene/import.h"

#include <assimp/BaseImporter.h>
#include <assimp/importerdesc.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_set>
#include <string_view>
#include <system_error>

#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"
#include "proxima/core/file_extension.h"
#include "proxima/core/image_io.h"
#include "proxima/core/limits.h"
#include "proxima/scene/obj_check.h"
#include "proxima/scene/ply_check.h"

// Debian's assimp 5.2 is built with its internal assertions on, and a failed one calls
// abort() — e.g. TriangulateProcess on a malformed PLY face list. This
// definition interposes the library's (its calls go through the PLT; the executables
// export it, see CMakeLists.txt): it throws instead, which assimp's importers and
// post-processing steps catch and report as a failed import.
namespace Assimp {
void aiAssertViolation(const char* expression, const char* file, int line) {
  throw std::runtime_error(std::string("assimp internal check failed: ") + expression + " (" + file + ":" +
                           std::to_string(line) + ")");
}
}  // namespace Assimp

namespace proxima {
namespace {

namespace fs = std::filesystem;

// Shininess range of the OBJ mapping: Ns in [0, kMaxNs] ↔ g in [1, 0].
constexpr double kMaxNs = 1000.0;

float gloss_from_shininess(float ns) {
  const double g = 1.0 - std::log(std::max(0.0, double(ns)) + 1.0) / std::log(kMaxNs + 1.0);
  return float(std::clamp(g, 0.0, 1.0));
}

double shininess_from_gloss(float g) {
  return std::pow(kMaxNs + 1.0, 1.0 - double(std::clamp(g, 0.0f, 1.0f))) - 1.0;
}

mat4 to_glm(const aiMatrix4x4& m) {
  // aiMatrix4x4 is row-major (a1..a4 is the first row); glm is column-major.
  mat4 r;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) r[col][row] = m[row][col];
  return r;
}

vec3 material_color(const aiMaterial& mat, const char* key, unsigned type, unsigned index,
                    vec3 fallback) {
  aiColor3D c;
  if (mat.Get(key, type, index, c) != aiReturn_SUCCESS) return fallback;
  return {c.r, c.g, c.b};
}

std::optional<float> material_float(const aiMaterial& mat, const char* key, unsigned type,
                                    unsigned index) {
  float f = 0.0f;
  if (mat.Get(key, type, index, f) != aiReturn_SUCCESS) return std::nullopt;
  return f;
}

void warn(const fs::path& file, const std::string& message) {
  std::fprintf(stderr, "warning: %s: %s\n", file.string().c_str(), message.c_str());
}

// Converts assimp's materials on first use and loads their textures (once per file).
class MaterialConverter {
 public:
  MaterialConverter(const fs::path& file, const aiScene& ai, Scene& scene)
      : file_(file), ai_(ai), scene_(scene) {}

  uint32_t get(unsigned ai_index) {
    if (ai_index >= ai_.mNumMaterials)
      fail_input(file_.string() + ": mesh references a missing material");
    auto it = ids_.find(ai_index);
    if (it != ids_.end()) return it->second;
    const uint32_t id = add_material(scene_, convert(*ai_.mMaterials[ai_index], ai_index));
    ids_.emplace(ai_index, id);
    return id;
  }

 private:
  Material convert(const aiMaterial& ai_mat, unsigned ai_index) {
    Material m;
    m.name = ai_mat.GetName().C_Str();
    if (m.name.empty()) m.name = "material" + std::to_string(ai_index);

    // glTF puts its base color in both keys; other formats only in the diffuse one.
    m.diffuse = material_color(ai_mat, AI_MATKEY_COLOR_DIFFUSE,
                               material_color(ai_mat, AI_MATKEY_BASE_COLOR, m.diffuse));
    m.emission = material_color(ai_mat, AI_MATKEY_COLOR_EMISSIVE, m.emission);

    // glTF's importer also fills shininess from roughness, so the PBR keys win when present.
    const auto metallic = material_float(ai_mat, AI_MATKEY_METALLIC_FACTOR);
    const auto roughness = material_float(ai_mat, AI_MATKEY_ROUGHNESS_FACTOR);
    if (metallic || roughness) {
      m.specular = metallic.value_or(0.0f);
      m.gloss = roughness.value_or(1.0f);
    } else {
      const vec3 ks = material_color(ai_mat, AI_MATKEY_COLOR_SPECULAR, vec3(0.0f));
      m.specular = std::max({ks.x, ks.y, ks.z});
      m.gloss = gloss_from_shininess(material_float(ai_mat, AI_MATKEY_SHININESS).value_or(0.0f));
    }

    if (!is_finite(m.diffuse) || !is_finite(m.emission) || !std::isfinite(m.specular) ||
        !std::isfinite(m.gloss))
      fail_input(file_.string() + ": material '" + m.name + "' has a non-finite value");
    m.specular = std::clamp(m.specular, 0.0f, 1.0f);
    m.gloss = std::clamp(m.gloss, 0.0f, 1.0f);
    m.diffuse_texture = texture(ai_mat, m.name);
    return m;
  }

  int texture(const aiMaterial& ai_mat, const std::string& material_name) {
    aiString ai_path;
    if (ai_mat.GetTexture(aiTextureType_DIFFUSE, 0, &ai_path) != aiReturn_SUCCESS &&
        ai_mat.GetTexture(aiTextureType_BASE_COLOR, 0, &ai_path) != aiReturn_SUCCESS)
      return -1;
    std::string rel = ai_path.C_Str();
    if (rel.empty()) return -1;
    if (rel[0] == '*' || ai_.GetEmbeddedTexture(rel.c_str()) != nullptr) {
      warn(file_, "material '" + material_name + "': embedded texture skipped");
      return -1;
    }
    std::replace(rel.begin(), rel.end(), '\\', '/');  // files written on Windows
    const fs::path tex_path = file_.parent_path() / rel;
    const std::string key = tex_path.lexically_normal().string();
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;

    // Models often ship without their pictures; the material color still renders.
    std::error_code ec;
    if (!fs::is_regular_file(tex_path, ec)) {
      warn(file_, "material '" + material_name + "': texture " + tex_path.string() +
                      " not found, using the diffuse color");
      textures_.emplace(key, -1);
      return -1;
    }
    Texture t;
    t.name = key;
    try {
      t.image = read_image_linear(tex_path, 3);
    } catch (const InputError& e) {
      fail_input(file_.string() + ": material '" + material_name + "': " + e.what());
    }
    const int id = int(scene_.textures.size());
    scene_.textures.push_back(std::move(t));
    textures_.emplace(key, id);
    return id;
  }

  const fs::path& file_;
  const aiScene& ai_;
  Scene& scene_;
  std::map<unsigned, uint32_t> ids_;
  std::map<std::string, int> textures_;  // normalized path → texture id (−1: missing)
};

Mesh convert_mesh(const aiMesh& ai_mesh, const mat4& transform) {
  Mesh mesh;
  mesh.positions.reserve(ai_mesh.mNumVertices);
  for (unsigned i = 0; i < ai_mesh.mNumVertices; ++i) {
    const aiVector3D& p = ai_mesh.mVertices[i];
    mesh.positions.emplace_back(p.x, p.y, p.z);
  }
  if (ai_mesh.HasNormals()) {
    mesh.normals.reserve(ai_mesh.mNumVertices);
    for (unsigned i = 0; i < ai_mesh.mNumVertices; ++i) {
      const aiVector3D& n = ai_mesh.mNormals[i];
      mesh.normals.emplace_back(n.x, n.y, n.z);
    }
  }
  if (ai_mesh.HasTextureCoords(0)) {
    mesh.uvs.reserve(ai_mesh.mNumVertices);
    for (unsigned i = 0; i < ai_mesh.mNumVertices; ++i) {
      const aiVector3D& t = ai_mesh.mTextureCoords[0][i];
      mesh.uvs.emplace_back(t.x, t.y);
    }
  }
  // After Triangulate + SortByPType a triangle mesh holds only 3-index faces; the size
  // check keeps a malformed face from reading past its index array.
  mesh.triangles.reserve(ai_mesh.mNumFaces);
  for (unsigned f = 0; f < ai_mesh.mNumFaces; ++f) {
    const aiFace& face = ai_mesh.mFaces[f];
    if (face.mNumIndices == 3)
      mesh.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
  }
  if (transform != mat4(1.0f)) transform_mesh(mesh, transform);  // also fixes mirrored winding
  return mesh;
}

// A node with its world transform.
struct NodeInstance {
  const aiNode* node;
  mat4 world;
};

// The node graph in depth-first order (parents first, children in order), without
// recursion: a file can nest nodes arbitrarily deep. A node reached twice means a corrupt
// graph (assimp's nodes form a tree); failing keeps a cycle from looping forever.
std::vector<NodeInstance> flatten_nodes(const fs::path& file, const aiNode& root) {
  std::vector<NodeInstance> out;
  std::vector<NodeInstance> stack{{&root, to_glm(root.mTransformation)}};
  std::unordered_set<const aiNode*> seen;
  while (!stack.empty()) {
    const NodeInstance n = stack.back();
    stack.pop_back();
    if (!seen.insert(n.node).second) fail_input(file.string() + ": node graph has a cycle");
    out.push_back(n);
    for (unsigned c = n.node->mNumChildren; c-- > 0;) {
      const aiNode* child = n.node->mChildren[c];
      if (child != nullptr) stack.push_back({child, n.world * to_glm(child->mTransformation)});
    }
  }
  return out;
}

// The triangle meshes a node instantiates (index checked: the graph comes from the file).
std::vector<const aiMesh*> node_meshes(const fs::path& file, const aiScene& ai, const aiNode& node) {
  std::vector<const aiMesh*> meshes;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    if (node.mMeshes[k] >= ai.mNumMeshes) fail_input(file.string() + ": node references a missing mesh");
    const aiMesh* mesh = ai.mMeshes[node.mMeshes[k]];
    if (mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) meshes.push_back(mesh);
  }
  return meshes;
}

void add_node(const fs::path& file, const aiScene& ai, const NodeInstance& n,
              MaterialConverter& materials, Scene& scene) {
  for (const aiMesh* ai_mesh : node_meshes(file, ai, *n.node)) {
    Mesh mesh = convert_mesh(*ai_mesh, n.world);
    if (mesh.triangles.empty()) continue;
    std::string name = ai_mesh->mName.C_Str();
    if (name.empty()) name = n.node->mName.C_Str();
    if (name.empty()) name = file.stem().string() + "_" + std::to_string(scene.objects.size());
    add_object(scene, mesh, name, materials.get(ai_mesh->mMaterialIndex));
  }
}

// ---- OBJ writing ------------------------------------------------------------

// Shortest decimal text that reads back as the same float.
void put(std::string& out, double v) {
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, ec == std::errc() ? end : buf);
}
void put(std::string& out, float v) {
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, ec == std::errc() ? end : buf);
}
void put(std::string& out, vec3 v) {
  put(out, v.x);
  out += ' ';
  put(out, v.y);
  out += ' ';
  put(out, v.z);
}

// OBJ names end at whitespace for many readers; keep them to one token.
std::string obj_token(const std::string& name, const std::string& fallback) {
  std::string t = name.empty() ? fallback : name;
  for (char& c : t)
    if (std::isspace(static_cast<unsigned char>(c)) || c == '#') c = '_';
  return t;
}

Scene import_assimp(const fs::path& path);

}  // namespace

// assimp's glTF reader, post-processing and aiNode destructor recurse once per nesting
// level; a 100000-deep glTF chain overflowed the stack. Rather than running assimp on a
// thread whose stack grows with the file, files nested deeper than kMaxNodeDepth /
// kMaxJsonNesting are refused before assimp reads them (check_json_nesting), so the
// recursion is bounded and the import runs on the caller's thread.
Scene import_mesh_file(const fs::path& path) { return import_assimp(path); }

namespace {

// The importers proxima is tested and fuzzed with (OBJ, PLY, glTF 2.0); assimp's other ~45
// (FBX, Collada, 3DS, …) would be reached by content sniffing even for a `.obj` file that
// OBJ's reader declines, and are neither tested nor fuzzed here.
constexpr const char* kImporters[] = {"Wavefront Object Importer", "Stanford Polygon Library (PLY) Importer",
                                      "glTF2 Importer"};
constexpr const char* kExtensions[] = {".obj", ".ply", ".gltf", ".glb"};

void keep_tested_importers(Assimp::Importer& importer) {
  std::vector<Assimp::BaseImporter*> others;
  for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
    const char* name = importer.GetImporterInfo(i)->mName;
    if (std::none_of(std::begin(kImporters), std::end(kImporters), [&](const char* k) { return std::strcmp(k, name) == 0; }))
      others.push_back(importer.GetImporter(i));
  }
  for (Assimp::BaseImporter* other : others) {
    importer.UnregisterLoader(other);
    delete other;  // the Importer deletes only the loaders still registered
  }
}

std::string file_head(const fs::path& path, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  return head;
}

// The glTF node graph: a forest (each node has at most one parent, no cycles), at most
// kMaxNodeDepth deep. assimp recurses along it, and on a cycle forever.
void check_node_graph(const std::string& file, const nlohmann::json& gltf) {
  if (!gltf.is_object() || !gltf.contains("nodes") || !gltf["nodes"].is_array()) return;
  const nlohmann::json& nodes = gltf["nodes"];
  const size_t n = nodes.size();
  auto fail = [&](const std::string& why) { fail_input(file + ": glTF node graph " + why); };
  std::vector<std::vector<size_t>> children(n);
  std::vector<int> parents(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (!nodes[i].is_object() || !nodes[i].contains("children") || !nodes[i]["children"].is_array()) continue;
    for (const nlohmann::json& c : nodes[i]["children"]) {
      if (!c.is_number_unsigned() || c.get<uint64_t>() >= n) fail("has a child index out of range in node " + std::to_string(i));
      const size_t child = c.get<size_t>();
      if (++parents[child] > 1) fail("is not a tree: node " + std::to_string(child) + " has two parents");
      children[i].push_back(child);
    }
  }
  std::vector<std::pair<size_t, int>> stack;  // (node, depth)
  size_t reached = 0;
  for (size_t i = 0; i < n; ++i)
    if (parents[i] == 0) stack.push_back({i, 1});
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    ++reached;
    if (depth > kMaxNodeDepth)
      fail("is more than " + std::to_string(kMaxNodeDepth) + " levels deep");
    for (size_t c : children[node]) stack.push_back({c, depth + 1});
  }
  if (reached != n) fail("has a cycle");
}

// A file assimp may read as glTF JSON (a `.gltf`, the JSON chunk of a `.glb`, or any file
// starting with `{` that the glTF reader would accept by content) must nest at most
// kMaxJsonNesting deep (rapidjson recurses per level) and have a sane node graph. nlohmann's
// parser does not recurse, so it can check what rapidjson would overflow on.
void check_json_nesting(const fs::path& path) {
  const std::string file = path.string();
  std::string head = file_head(path, 20);
  std::string json_text;
  if (head.size() >= 4 && head.compare(0, 4, "glTF") == 0) {
    // GLB: 12-byte header, then chunk 0 = (length, "JSON", bytes).
    std::ifstream in(path, std::ios::binary);
    unsigned char h[20] = {};
    in.read(reinterpret_cast<char*>(h), 20);
    if (in.gcount() < 20) return;  // assimp reports the truncated header
    const uint32_t length = uint32_t(h[12]) | uint32_t(h[13]) << 8 | uint32_t(h[14]) << 16 | uint32_t(h[15]) << 24;
    if (std::memcmp(h + 16, "JSON", 4) != 0) return;  // not glTF 2.0 GLB: assimp refuses it
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(path, ec);
    if (ec || length > bytes - 20) fail_input(file + ": GLB JSON chunk is longer than the file");
    json_text.resize(length);
    in.read(json_text.data(), std::streamsize(length));
  } else {
    const size_t first = head.find_first_not_of(" \t\r\n");
    if (first == std::string::npos || (head[first] != '{' && head[first] != '[')) return;
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    json_text = text.str();
  }
  // Nesting first, by a scan (nlohmann's callback parser is quadratic on long arrays).
  int depth = 0;
  bool in_string = false, escaped = false;
  for (const char c : json_text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonNesting)
        fail_input(file + ": JSON nested more than " + std::to_string(kMaxJsonNesting) + " levels deep");
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  nlohmann::json gltf;
  try {
    gltf = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception&) {
    return;  // not JSON after all (an OBJ starting with `{`?): assimp decides
  }
  check_node_graph(file, gltf);
}

void check_extension(const fs::path& path) {
  const std::string ext = lowercase_extension(path);
  if (std::none_of(std::begin(kExtensions), std::end(kExtensions), [&](const char* k) { return ext == k; }))
    fail_input(path.string() + ": unsupported mesh format '" + ext +
               "' (mesh files are .obj, .ply, .gltf or .glb; convert others to glTF)");
}

// What assimp's importer built, checked before any post-processing step reads it:
// ValidateDataStructure skips the face checks of a mesh whose primitive types are not set
// yet (the PLY reader leaves them 0), so a face without indices or one pointing past the
// vertex array would reach Triangulate and the steps after it. The triangle count after
// triangulation (n − 2 per n-gon) is checked against the limits here too, before the steps
// allocate for it.
void check_imported_meshes(const std::string& file, const aiScene& ai) {
  uint64_t triangles = 0, vertices = 0;
  for (unsigned m = 0; m < ai.mNumMeshes; ++m) {
    const aiMesh* mesh = ai.mMeshes[m];
    const std::string where = file + ": mesh " + std::to_string(m);
    if (mesh == nullptr || (mesh->mNumVertices > 0 && mesh->mVertices == nullptr) ||
        (mesh->mNumFaces > 0 && mesh->mFaces == nullptr))
      fail_input(where + " is incomplete");
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr)
        fail_input(where + ": face " + std::to_string(f) + " has no vertex indices");
      if (face.mNumIndices > unsigned(kMaxFaceVertices))  // before Triangulate's ear clipping
        fail_input(where + ": face " + std::to_string(f) + " has " + std::to_string(face.mNumIndices) +
                   " vertices, more than " + std::to_string(kMaxFaceVertices));
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= mesh->mNumVertices)
          fail_input(where + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(face.mIndices[k]) +
                     " of " + std::to_string(mesh->mNumVertices));
      if (face.mNumIndices >= 3) triangles += face.mNumIndices - 2;
    }
    vertices += mesh->mNumVertices;
  }
  check_geometry_budget(file, triangles, vertices);
}

Scene import_assimp(const fs::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) fail_missing_file(file + ": no such file");
  if (!fs::is_regular_file(path, ec)) fail_input(file + ": not a regular file");

  check_extension(path);
  check_ply_file(path);
  check_obj_indices(path);
  check_json_nesting(path);
  Assimp::Importer importer;
  keep_tested_importers(importer);
  // SortByPType puts lines and points into meshes of their own, which add_node skips.
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_GenSmoothNormals | aiProcess_SortByPType |
                         aiProcess_ValidateDataStructure;
  // Read first, post-process after proxima's own checks: assimp's steps trust what its
  // importer built, and a malformed file can build nonsense (check_imported_meshes).
  const aiScene* ai = nullptr;
  try {
    ai = importer.ReadFile(file, aiProcess_ValidateDataStructure);
  } catch (const std::exception& e) {  // assimp catches its own errors, but not every one
    fail_input(file + ": " + e.what());
  }
  if (ai == nullptr) fail_input(file + ": " + importer.GetErrorString());
  check_imported_meshes(file, *ai);
  try {
    ai = importer.ApplyPostProcessing(flags);  // validates again, now with primitive types set
  } catch (const std::exception& e) {
    fail_input(file + ": " + e.what());
  }
  if (ai == nullptr) fail_input(file + ": " + importer.GetErrorString());
  if ((ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || ai->mRootNode == nullptr)
    fail_input(file + ": no triangles");

  Scene scene;
  scene.name = path.stem().string();
  const std::vector<NodeInstance> nodes = flatten_nodes(path, *ai->mRootNode);
  // Instancing multiplies geometry: check the flattened size before building it.
  uint64_t triangles = 0, vertices = 0;
  for (const NodeInstance& n : nodes)
    for (const aiMesh* mesh : node_meshes(path, *ai, *n.node)) {
      triangles += mesh->mNumFaces;
      vertices += mesh->mNumVertices;
    }
  check_geometry_budget(file, triangles, vertices);
  MaterialConverter materials(path, *ai, scene);
  for (const NodeInstance& n : nodes) add_node(path, *ai, n, materials, scene);
  if (scene.triangles.empty()) fail_input(file + ": no triangles");
  return scene;
}

}  // namespace

void write_obj(const fs::path& path, const Scene& scene) {
  const fs::path mtl_path = fs::path(path).replace_extension(".mtl");
  const std::string stem = path.stem().string();

  // Materials; textures become PNG files beside the OBJ so the result is self-contained.
  std::vector<std::string> material_names;
  std::set<std::string> used_names;
  std::string mtl = "# proxima material library: Ks = (s, s, s), Ns = 1001^(1 - g) - 1\n";
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    std::string name = obj_token(m.name, "material" + std::to_string(i));
    if (!used_names.insert(name).second) {
      name += "_" + std::to_string(i);
      used_names.insert(name);
    }
    material_names.push_back(name);
    mtl += "\nnewmtl " + name + "\nKd ";
    put(mtl, m.diffuse);
    mtl += "\nKs ";
    put(mtl, vec3(m.specular));
    mtl += "\nNs ";
    put(mtl, shininess_from_gloss(m.gloss));
    mtl += "\nKe ";
    put(mtl, m.emission);
    mtl += "\nillum 2\n";
    if (m.diffuse_texture >= 0 && size_t(m.diffuse_texture) < scene.textures.size()) {
      const std::string tex = stem + "_texture" + std::to_string(m.diffuse_texture) + ".png";
      write_png_linear(path.parent_path() / tex, scene.textures[size_t(m.diffuse_texture)].image);
      mtl += "map_Kd " + tex + "\n";
    }
  }
  write_text_file(mtl_path, mtl);

  const bool has_normals = scene.normals.size() == scene.positions.size();
  const bool has_uvs = scene.uvs.size() == scene.positions.size();
  std::string obj = "# written by proxima\nmtllib " + mtl_path.filename().string() + "\n";
  for (const vec3& p : scene.positions) {
    obj += "v ";
    put(obj, p);
    obj += '\n';
  }
  if (has_normals)
    for (const vec3& n : scene.normals) {
      obj += "vn ";
      put(obj, n);
      obj += '\n';
    }
  if (has_uvs)
    for (const vec2& t : scene.uvs) {
      obj += "vt ";
      put(obj, t.x);
      obj += ' ';
      put(obj, t.y);
      obj += '\n';
    }
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    obj += "o " + obj_token(object.name, "object" + std::to_string(o)) + "\n";
    uint32_t current = UINT32_MAX;
    for (uint32_t t = object.first_triangle; t < object.first_triangle + object.triangle_count;
         ++t) {
      const uint32_t material = scene.triangle_material[t];
      if (material != current && material < material_names.size()) {
        obj += "usemtl " + material_names[material] + "\n";
        current = material;
      }
      obj += 'f';
      for (int k = 0; k < 3; ++k) {
        const std::string i = std::to_string(scene.triangles[t][k] + 1);  // OBJ is 1-based
        obj += ' ' + i;
        if (has_uvs || has_normals) obj += '/' + (has_uvs ? i : std::string());
        if (has_normals) obj += '/' + i;
      }
      obj += '\n';
    }
  }
  write_text_file(path, obj);
}

}  // namespace proxima
