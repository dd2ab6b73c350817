// JSON scene files (docs/formats.md has the format and a worked example).
// Every value is checked as it is read; an error names the file and the JSON path of the
// offending value, e.g. "scene.json: objects[2].radius: must be > 0". nlohmann-json stays
// inside this file and its exceptions are converted to InputError at the boundary.
#include "proxima/scene/scene_file.h"

#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string_view>

#include "proxima/core/error.h"
#include "proxima/core/file_extension.h"
#include "proxima/core/image_io.h"
#include "proxima/core/limits.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/import.h"
#include "proxima/scene/procedural.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Upper bounds that keep a typo from allocating gigabytes.
constexpr int kMaxSegments = 4096;
constexpr int kMaxTessellation = 256;
constexpr int kMaxFrames = 1000000;

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// A JSON value with its path from the document root, for error messages.
class Node {
 public:
  Node(const json& j, std::string path, const std::string& file)
      : j_(j), path_(std::move(path)), file_(file) {}

  [[noreturn]] void fail(const std::string& message) const {
    fail_input(file_ + ": " + (path_.empty() ? std::string("top level") : path_) + ": " + message);
  }

  // ---- objects ----
  // Fails unless this is an object whose keys are all in `allowed`.
  void expect_keys(const std::vector<std::string_view>& allowed) const {
    expect_object();
    for (const auto& item : j_.items()) {
      bool known = false;
      for (std::string_view a : allowed) known = known || item.key() == a;
      if (known) continue;
      std::vector<std::string> names(allowed.begin(), allowed.end());
      child(item.key()).fail("unknown key (expected one of: " + join(names) + ")");
    }
  }
  bool has(const std::string& key) const { return j_.contains(key); }
  Node operator[](const std::string& key) const {
    if (!has(key)) fail("missing required key '" + key + "'");
    return child(key);
  }
  std::vector<std::pair<std::string, Node>> members() const {
    expect_object();
    std::vector<std::pair<std::string, Node>> out;
    for (const auto& item : j_.items()) out.emplace_back(item.key(), child(item.key()));
    return out;
  }

  // Reads `key` with `read` when present, else returns `fallback`.
  template <typename T>
  T get(const std::string& key, T (Node::*read)() const, T fallback) const {
    return has(key) ? (child(key).*read)() : fallback;
  }
  int get_int(const std::string& key, int lo, int hi, int fallback) const {
    return has(key) ? child(key).integer(lo, hi) : fallback;
  }

  void expect_object() const {
    if (!j_.is_object()) fail(std::string("must be an object, not ") + j_.type_name());
  }

  // ---- arrays ----
  std::vector<Node> items() const {
    if (!j_.is_array()) fail(std::string("must be an array, not ") + j_.type_name());
    std::vector<Node> out;
    for (size_t i = 0; i < j_.size(); ++i)
      out.emplace_back(j_[i], path_ + "[" + std::to_string(i) + "]", file_);
    return out;
  }
  std::vector<Node> items(size_t n) const {
    std::vector<Node> out = items();
    if (out.size() != n)
      fail("must have " + std::to_string(n) + " elements, not " + std::to_string(out.size()));
    return out;
  }

  // ---- scalars ----
  float number() const {
    if (!j_.is_number()) fail(std::string("must be a number, not ") + j_.type_name());
    const float v = j_.get<float>();
    if (!std::isfinite(v)) fail("must be a finite number");
    return v;
  }
  float positive() const {
    const float v = number();
    if (!(v > 0.0f)) fail("must be > 0");
    return v;
  }
  float non_negative() const {
    const float v = number();
    if (v < 0.0f) fail("must be >= 0");
    return v;
  }
  float unit() const {
    const float v = number();
    if (v < 0.0f || v > 1.0f) fail("must be in [0, 1]");
    return v;
  }
  float fov() const {
    const float v = number();
    if (!(v > 0.0f && v < 180.0f)) fail("must be in (0, 180) degrees");
    return v;
  }
  int integer(int lo, int hi) const {
    const float v = number();
    if (v != std::floor(v)) fail("must be an integer");
    if (v < float(lo) || v > float(hi))
      fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return int(v);
  }
  bool boolean() const {
    if (!j_.is_boolean()) fail(std::string("must be true or false, not ") + j_.type_name());
    return j_.get<bool>();
  }
  std::string string() const {
    if (!j_.is_string()) fail(std::string("must be a string, not ") + j_.type_name());
    std::string s = j_.get<std::string>();
    if (s.empty()) fail("must not be empty");
    return s;
  }
  vec3 vector3() const {
    const std::vector<Node> e = items(3);
    return {e[0].number(), e[1].number(), e[2].number()};
  }
  // [r, g, b] or one number for gray; components ≥ 0.
  vec3 color() const {
    if (j_.is_number()) return vec3(non_negative());
    const std::vector<Node> e = items(3);
    return {e[0].non_negative(), e[1].non_negative(), e[2].non_negative()};
  }
  // One non-zero number (uniform) or three.
  vec3 scale() const {
    const vec3 s = j_.is_number() ? vec3(number()) : vector3();
    if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) fail("scale factors must be non-zero");
    return s;
  }

 private:
  Node child(const std::string& key) const {
    return Node(j_.at(key), path_.empty() ? key : path_ + "." + key, file_);
  }

  const json& j_;
  std::string path_;
  const std::string& file_;
};

// Rotation by Euler angles in degrees: about X first, then Y, then Z (fixed world axes),
// i.e. R = Rz · Ry · Rx.
quat rotation_xyz_deg(vec3 deg) {
  const vec3 r = glm::radians(deg);
  return glm::angleAxis(r.z, vec3(0, 0, 1)) * glm::angleAxis(r.y, vec3(0, 1, 0)) *
         glm::angleAxis(r.x, vec3(1, 0, 0));
}

struct Transform {
  vec3 translate{0.0f};
  quat rotate{1.0f, 0.0f, 0.0f, 0.0f};
  vec3 scale{1.0f};

  // M = T · R · S.
  mat4 matrix() const {
    return glm::translate(mat4(1.0f), translate) * glm::mat4_cast(rotate) *
           glm::scale(mat4(1.0f), scale);
  }
};

Transform read_transform(const Node& n) {
  n.expect_keys({"translate", "rotate_deg", "scale"});
  Transform t;
  t.translate = n.get("translate", &Node::vector3, t.translate);
  t.rotate = rotation_xyz_deg(n.get("rotate_deg", &Node::vector3, vec3(0.0f)));
  t.scale = n.get("scale", &Node::scale, t.scale);
  return t;
}

// Keys strictly increasing in time.
float read_key_time(const Node& key, float previous, bool first) {
  const float time = key["time"].number();
  if (!first && !(time > previous)) key["time"].fail("key times must increase strictly");
  return time;
}

RigidAnimation read_animation(const Node& n, vec3 default_pivot) {
  n.expect_keys({"pivot", "loop", "keys"});
  RigidAnimation anim;
  anim.pivot = n.get("pivot", &Node::vector3, default_pivot);
  anim.loop = n.get("loop", &Node::boolean, false);
  const std::vector<Node> keys = n["keys"].items();
  if (keys.empty()) n["keys"].fail("must have at least one key");
  for (const Node& k : keys) {
    k.expect_keys({"time", "translate", "rotate_deg"});
    RigidKey key;
    key.time =
        read_key_time(k, anim.keys.empty() ? 0.0f : anim.keys.back().time, anim.keys.empty());
    key.translation = k.get("translate", &Node::vector3, vec3(0.0f));
    key.rotation = rotation_xyz_deg(k.get("rotate_deg", &Node::vector3, vec3(0.0f)));
    anim.keys.push_back(key);
  }
  return anim;
}

// The triangles and vertices of one object of `scene`, re-indexed from 0.
Mesh extract_object(const Scene& scene, const Object& o) {
  Mesh mesh;
  const auto first = scene.positions.begin() + o.first_vertex;
  mesh.positions.assign(first, first + o.vertex_count);
  if (scene.normals.size() == scene.positions.size())
    mesh.normals.assign(scene.normals.begin() + o.first_vertex,
                        scene.normals.begin() + o.first_vertex + o.vertex_count);
  if (scene.uvs.size() == scene.positions.size())
    mesh.uvs.assign(scene.uvs.begin() + o.first_vertex,
                    scene.uvs.begin() + o.first_vertex + o.vertex_count);
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t)
    mesh.triangles.push_back(scene.triangles[t] - uvec3(o.first_vertex));
  return mesh;
}

class SceneReader {
 public:
  explicit SceneReader(const fs::path& path) : path_(path), file_(path.string()) {}

  Scene read(const json& doc) {
    const Node root(doc, "", file_);
    root.expect_keys({"name", "builtin", "materials", "objects", "cameras", "camera_paths",
                      "lights", "environment", "ambient", "probe_box"});
    if (root.has("builtin")) read_builtin(root["builtin"]);
    scene_.name = root.get("name", &Node::string, path_.stem().string());
    for (uint32_t m = 0; m < scene_.materials.size(); ++m)
      materials_[scene_.materials[m].name] = m;  // a builtin's materials can be referenced
    if (root.has("materials")) read_materials(root["materials"]);
    if (root.has("objects"))
      for (const Node& o : root["objects"].items()) read_object(o);
    if (root.has("cameras"))
      for (const Node& c : root["cameras"].items()) read_camera(c);
    if (root.has("camera_paths"))
      for (const Node& p : root["camera_paths"].items()) read_camera_path(p);
    if (root.has("lights"))
      for (const Node& l : root["lights"].items()) read_light(l);
    if (root.has("environment")) read_environment(root["environment"]);
    scene_.ambient = root.get("ambient", &Node::color, scene_.ambient);
    if (root.has("probe_box")) read_probe_box(root["probe_box"]);
    if (scene_.triangles.empty())
      root.fail("the scene has no geometry (give \"objects\" or a \"builtin\" scene)");
    return std::move(scene_);
  }

 private:
  fs::path resolve(const std::string& relative) const { return path_.parent_path() / relative; }

  // Fails at `n` when adding this much geometry would take the scene over the limits.
  void check_budget(const Node& n, uint64_t triangles, uint64_t vertices) const {
    const std::string error = geometry_budget_error(scene_.triangles.size() + triangles,
                                                    scene_.positions.size() + vertices);
    if (!error.empty()) n.fail(error);
  }

  void read_builtin(const Node& n) {
    const std::string name = n.string();
    if (!is_builtin_scene(name)) {
      std::vector<std::string> names;
      for (const BuiltinSceneInfo& b : builtin_scenes()) names.push_back(b.name);
      n.fail("unknown built-in scene '" + name + "' (built-in scenes: " + join(names) + ")");
    }
    scene_ = make_builtin_scene(name);
  }

  int load_texture(const Node& n) {
    const fs::path p = resolve(n.string());
    const std::string key = p.lexically_normal().string();
    for (size_t i = 0; i < scene_.textures.size(); ++i)
      if (scene_.textures[i].name == key) return int(i);
    Texture t;
    t.name = key;
    try {
      t.image = read_image_linear(p, 3);
    } catch (const InputError& e) {
      n.fail(e.what());
    }
    scene_.textures.push_back(std::move(t));
    return int(scene_.textures.size() - 1);
  }

  void read_materials(const Node& list) {
    std::map<std::string, bool> seen;
    for (const Node& n : list.items()) {
      n.expect_keys({"name", "diffuse", "texture", "specular", "gloss", "emission"});
      Material m;
      m.name = n["name"].string();
      if (seen[m.name]) n["name"].fail("duplicate material name '" + m.name + "'");
      seen[m.name] = true;
      m.diffuse = n.get("diffuse", &Node::color, m.diffuse);
      if (n.has("texture")) m.diffuse_texture = load_texture(n["texture"]);
      m.specular = n.get("specular", &Node::unit, m.specular);
      m.gloss = n.get("gloss", &Node::unit, m.gloss);
      m.emission = n.get("emission", &Node::color, m.emission);
      materials_[m.name] = add_material(scene_, m);
    }
  }

  uint32_t material(const Node& n) {
    const std::string name = n.string();
    auto it = materials_.find(name);
    if (it == materials_.end()) n.fail("unknown material '" + name + "'");
    return it->second;
  }

  // The material of objects that name none: the Material defaults (gray, diffuse).
  uint32_t default_material() {
    if (!default_material_) {
      Material m;
      m.name = "default";
      default_material_ = add_material(scene_, m);
    }
    return *default_material_;
  }

  void read_object(const Node& n) {
    const std::string type = n["type"].string();
    const std::vector<std::string_view> common = {"type", "name", "material", "transform",
                                                  "animation"};
    auto keys = [&](std::initializer_list<std::string_view> extra) {
      std::vector<std::string_view> all = common;
      all.insert(all.end(), extra);
      return all;
    };
    std::vector<std::string_view> allowed;
    if (type == "mesh") {
      allowed = keys({"file", "material_overrides"});
    } else if (type == "sphere") {
      allowed = keys({"radius", "segments", "rings"});
    } else if (type == "cylinder") {
      allowed = keys({"radius", "height", "segments", "rings", "capped"});
    } else if (type == "torus") {
      allowed = keys({"major_radius", "minor_radius", "major_segments", "minor_segments"});
    } else if (type == "box") {
      allowed = keys({"size", "subdivisions"});
    } else if (type == "plane") {
      allowed = keys({"size", "subdivisions"});
    } else if (type == "teapot") {
      allowed = keys({"tessellation"});
    } else {
      n["type"].fail("unknown object type '" + type +
                     "' (expected mesh, sphere, cylinder, torus, box, plane or teapot)");
    }
    n.expect_keys(allowed);

    const Transform transform = n.has("transform") ? read_transform(n["transform"]) : Transform{};
    const RigidAnimation animation =
        n.has("animation") ? read_animation(n["animation"], transform.translate) : RigidAnimation{};
    const std::string name =
        n.get("name", &Node::string, type + std::to_string(scene_.objects.size()));

    if (type == "mesh") {
      read_mesh_object(n, name, transform.matrix(), animation);
      return;
    }
    // Each generator's triangle and (upper bound) vertex count (procedural.h) is checked
    // against the limits before it allocates.
    Mesh mesh;
    if (type == "sphere") {
      const float radius = n["radius"].positive();
      const uint64_t seg = n.get_int("segments", 3, kMaxSegments, 32);
      const uint64_t rings = n.get_int("rings", 2, kMaxSegments, 16);
      check_budget(n, 2 * seg * (rings - 1), (seg + 1) * (rings + 1));
      mesh = make_sphere(radius, int(seg), int(rings));
    } else if (type == "cylinder") {
      const float radius = n["radius"].positive(), height = n["height"].positive();
      const uint64_t seg = n.get_int("segments", 3, kMaxSegments, 32);
      const uint64_t rings = n.get_int("rings", 1, kMaxSegments, 1);
      const bool capped = n.get("capped", &Node::boolean, true);
      check_budget(n, 2 * seg * rings + 2 * seg, (seg + 1) * (rings + 1) + 2 * (seg + 2));
      mesh = make_cylinder(radius, height, int(seg), int(rings), capped);
    } else if (type == "torus") {
      const float major = n["major_radius"].positive(), minor = n["minor_radius"].positive();
      const uint64_t a = n.get_int("major_segments", 3, kMaxSegments, 48);
      const uint64_t b = n.get_int("minor_segments", 3, kMaxSegments, 24);
      check_budget(n, 2 * a * b, (a + 1) * (b + 1));
      mesh = make_torus(major, minor, int(a), int(b));
    } else if (type == "box") {
      const Node size = n["size"];
      vec3 s = size.vector3();
      if (!(s.x > 0.0f && s.y > 0.0f && s.z > 0.0f)) size.fail("sizes must be > 0");
      const uint64_t sub = n.get_int("subdivisions", 1, kMaxSegments, 1);
      check_budget(n, 12 * sub * sub, 6 * (sub + 1) * (sub + 1));
      mesh = make_box(s, int(sub));
    } else if (type == "plane") {
      const std::vector<Node> size = n["size"].items(2);
      uint64_t sub_x = 1, sub_z = 1;
      if (n.has("subdivisions")) {
        const std::vector<Node> sub = n["subdivisions"].items(2);
        sub_x = sub[0].integer(1, kMaxSegments);
        sub_z = sub[1].integer(1, kMaxSegments);
      }
      const float size_x = size[0].positive(), size_z = size[1].positive();
      check_budget(n, 2 * sub_x * sub_z, (sub_x + 1) * (sub_z + 1));
      mesh = make_plane(size_x, size_z, int(sub_x), int(sub_z));
    } else {  // teapot
      const uint64_t t = n.get_int("tessellation", 1, kMaxTessellation, 8);
      check_budget(n, 64 * t * t, 32 * (t + 1) * (t + 1));
      mesh = make_teapot(int(t));
    }
    transform_mesh(mesh, transform.matrix());
    const uint32_t mat = n.has("material") ? material(n["material"]) : default_material();
    add_object(scene_, mesh, name, mat, animation);
  }

  // A mesh file: one scene object per object of the file, all with the entry's transform
  // and animation; materials from the file unless overridden.
  void read_mesh_object(const Node& n, const std::string& name, const mat4& transform,
                        const RigidAnimation& animation) {
    const Node file_node = n["file"];
    Scene imported;
    try {
      imported = import_mesh_file(resolve(file_node.string()));
    } catch (const InputError& e) {
      file_node.fail(e.what());
    }
    check_budget(file_node, imported.triangles.size(), imported.positions.size());

    // Imported material id → scene material id.
    std::vector<std::optional<uint32_t>> remap(imported.materials.size());
    if (n.has("material") && n.has("material_overrides"))
      n.fail("give either 'material' or 'material_overrides', not both");
    if (n.has("material")) remap.assign(remap.size(), material(n["material"]));
    if (n.has("material_overrides")) {
      for (const auto& [key, value] : n["material_overrides"].members()) {
        bool found = false;
        for (size_t m = 0; m < imported.materials.size(); ++m)
          if (imported.materials[m].name == key) {
            remap[m] = material(value);
            found = true;
          }
        if (!found) value.fail("no material named '" + key + "' in " + file_node.string());
      }
    }
    // The file's materials (and their textures, shared by file name) enter the scene on
    // first use, so overridden ones leave nothing behind.
    auto scene_material = [&](uint32_t m) {
      if (!remap[m]) {
        Material copy = imported.materials[m];
        if (copy.diffuse_texture >= 0) {
          const Texture& t = imported.textures[size_t(copy.diffuse_texture)];
          copy.diffuse_texture = -1;
          for (size_t i = 0; i < scene_.textures.size() && copy.diffuse_texture < 0; ++i)
            if (scene_.textures[i].name == t.name) copy.diffuse_texture = int(i);
          if (copy.diffuse_texture < 0) {
            copy.diffuse_texture = int(scene_.textures.size());
            scene_.textures.push_back(t);
          }
        }
        remap[m] = add_material(scene_, copy);
      }
      return *remap[m];
    };

    for (const Object& o : imported.objects) {
      Mesh mesh = extract_object(imported, o);
      transform_mesh(mesh, transform);
      const std::string object_name = imported.objects.size() == 1 ? name : name + "/" + o.name;
      const uint32_t first_material = scene_material(imported.triangle_material[o.first_triangle]);
      const uint32_t id = add_object(scene_, mesh, object_name, first_material, animation);
      // An imported object may mix materials; add_object gave it one.
      const Object& added = scene_.objects[id];
      for (uint32_t t = 0; t < o.triangle_count; ++t)
        scene_.triangle_material[added.first_triangle + t] =
            scene_material(imported.triangle_material[o.first_triangle + t]);
    }
  }

  void read_camera(const Node& n) {
    n.expect_keys(
        {"name", "position", "target", "up", "vfov_deg", "near", "far", "width", "height"});
    NamedCamera c;
    c.name = n.get("name", &Node::string, "camera" + std::to_string(scene_.cameras.size()));
    const vec3 position = n["position"].vector3();
    const vec3 target = n["target"].vector3();
    const vec3 up = n.get("up", &Node::vector3, vec3(0, 1, 0));
    check_view(n, position, target, up);
    const float near = n.get("near", &Node::positive, 0.01f);
    const float far = n.get("far", &Node::positive, 1000.0f);
    if (!(far > near)) n["far"].fail("must be > near");
    c.camera = look_at(position, target, up, n.get("vfov_deg", &Node::fov, 60.0f),
                       n.get_int("width", 1, kMaxImageSide, 512),
                       n.get_int("height", 1, kMaxImageSide, 512), near, far);
    scene_.cameras.push_back(c);
  }

  // position ≠ target, and up not parallel to the view direction.
  static void check_view(const Node& n, vec3 position, vec3 target, vec3 up) {
    const vec3 dir = target - position;
    if (!(glm::length(dir) > 0.0f)) n["target"].fail("must differ from position");
    if (!(glm::length(glm::cross(glm::normalize(dir), up)) > 1e-6f * glm::length(up)))
      n.fail("up must not be zero or parallel to target − position");
  }

  void read_camera_path(const Node& n) {
    n.expect_keys({"name", "frames", "up", "keys"});
    CameraPath path;
    path.name = n.get("name", &Node::string, "path" + std::to_string(scene_.camera_paths.size()));
    path.frames = n.get_int("frames", 1, kMaxFrames, path.frames);
    path.up = n.get("up", &Node::vector3, path.up);
    const std::vector<Node> keys = n["keys"].items();
    if (keys.empty()) n["keys"].fail("must have at least one key");
    for (const Node& k : keys) {
      k.expect_keys({"time", "position", "target", "vfov_deg"});
      CameraKey key;
      key.time =
          read_key_time(k, path.keys.empty() ? 0.0f : path.keys.back().time, path.keys.empty());
      key.position = k["position"].vector3();
      key.target = k["target"].vector3();
      key.vfov_deg = k.get("vfov_deg", &Node::fov, key.vfov_deg);
      check_view(k, key.position, key.target, path.up);
      path.keys.push_back(key);
    }
    scene_.camera_paths.push_back(path);
  }

  void read_light(const Node& n) {
    const std::string type = n["type"].string();
    if (type == "point") {
      n.expect_keys({"type", "position", "intensity"});
      scene_.point_lights.push_back({n["position"].vector3(), n["intensity"].color()});
    } else if (type == "area") {
      n.expect_keys({"type", "corner", "edge_u", "edge_v", "radiance"});
      AreaLight l{n["corner"].vector3(), n["edge_u"].vector3(), n["edge_v"].vector3(),
                  n["radiance"].color()};
      if (!(l.area() > 0.0f)) n.fail("edge_u and edge_v must span a rectangle of area > 0");
      scene_.area_lights.push_back(l);
    } else {
      n["type"].fail("unknown light type '" + type + "' (expected point or area)");
    }
  }

  void read_probe_box(const Node& n) {
    n.expect_keys({"min", "max"});
    const vec3 lo = n["min"].vector3(), hi = n["max"].vector3();
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) n.fail("min must be below max on every axis");
    scene_.probe_box = {lo, hi};
  }

  void read_environment(const Node& n) {
    n.expect_keys({"color", "cube"});
    scene_.environment.color = n.get("color", &Node::color, scene_.environment.color);
    if (!n.has("cube")) return;
    const std::vector<Node> faces = n["cube"].items(6);
    for (size_t f = 0; f < 6; ++f) {
      ImageF image = read_face(faces[f]);
      if (image.width() != image.height() ||
          (f > 0 && image.width() != scene_.environment.cube[0].width()))
        faces[f].fail("face is " + std::to_string(image.width()) + "x" +
                      std::to_string(image.height()) +
                      "; faces must be square and all the same size");
      scene_.environment.cube[f] = std::move(image);
    }
  }

  // EXR faces keep their float range; other formats are decoded from sRGB. 3 channels.
  ImageF read_face(const Node& n) const {
    const fs::path p = resolve(n.string());
    try {
      if (lowercase_extension(p) != ".exr") return read_image_linear(p, 3);
      const ImageF exr = read_exr(p);
      ImageF rgb(exr.width(), exr.height(), 3);
      for (int y = 0; y < exr.height(); ++y)
        for (int x = 0; x < exr.width(); ++x)
          for (int c = 0; c < 3; ++c)
            rgb.at(x, y, c) = exr.at(x, y, std::min(c, exr.channels() - 1));
      return rgb;
    } catch (const InputError& e) {
      n.fail(e.what());
    }
  }

  fs::path path_;
  std::string file_;
  Scene scene_;
  std::map<std::string, uint32_t> materials_;
  std::optional<uint32_t> default_material_;
};

// "[json.exception.parse_error.101] parse error at line 3, column 5: …" → the part from
// "parse error" on, which names line and column.
std::string parse_error_text(const json::parse_error& e) {
  const std::string what = e.what();
  const size_t start = what.find("] ");
  return start == std::string::npos ? what : what.substr(start + 2);
}

}  // namespace

Scene load_scene_file(const fs::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_input(file + ": cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) fail_input(file + ": read error");

  try {
    // Comments (// and /* */) are allowed: scene files are written by hand.
    const json doc = json::parse(text.str(), nullptr, true, true);
    return SceneReader(path).read(doc);
  } catch (const json::parse_error& e) {
    fail_input(file + ": JSON " + parse_error_text(e));
  } catch (const json::exception& e) {  // Node checks types first; this is a backstop
    fail_input(file + ": " + e.what());
  }
}

}  // namespace proxima
