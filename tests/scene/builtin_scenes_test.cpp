// Built-in scenes: minimum sizes, reflector and camera counts, determinism, valid indices,
// and the exact Cornell layout other tests rely on.
#include "proxima/scene/builtin_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "proxima/core/error.h"

namespace proxima {
namespace {

size_t reflective_objects(const Scene& s) {
  std::set<uint32_t> objects;
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    if (s.materials[s.triangle_material[t]].reflective()) objects.insert(s.triangle_object[t]);
  }
  return objects.size();
}

size_t reflective_triangles(const Scene& s) {
  size_t n = 0;
  for (uint32_t m : s.triangle_material) n += s.materials[m].reflective() ? 1 : 0;
  return n;
}

const Object* find_object(const Scene& s, const std::string& name) {
  for (const Object& o : s.objects) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

struct Minimum {
  const char* name;
  size_t triangles;
  size_t reflectors;
  size_t camera_paths;
  size_t cameras;
  bool cameras_inside = true;  // outdoor scenes view their bounds from outside
};

// Names the parameter in test listings instead of dumping its bytes.
void PrintTo(const Minimum& m, std::ostream* os) { *os << m.name; }

constexpr Minimum kMinimums[] = {
    {"cornell", 7 * 128, 2, 0, 1},
    {"room-reflector", 2176, 1, 1, 2},
    {"living-room", 250000, 20, 2, 2},
    {"bathroom", 80000, 10, 2, 2},
    {"nest", 60000, 0, 0, 1, false},
    {"grass", 50000, 0, 0, 1, false},
    {"city", 45000, 0, 0, 1, false},
    {"tree", 100000, 0, 0, 1, false},
    {"room-teapot", 39800, 1, 1, 2},
    {"room-car", 39936, 1, 1, 2},
    {"room-parallax", 2176, 1, 0, 2},
};

TEST(BuiltinScenes, ListNamesTheFourScenes) {
  std::vector<BuiltinSceneInfo> list = builtin_scenes();
  // The four interiors come first; other modules append their test scenes after them.
  ASSERT_GE(list.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(list[i].name, kMinimums[i].name);
    EXPECT_FALSE(list[i].description.empty());
    EXPECT_TRUE(is_builtin_scene(list[i].name));
  }
  EXPECT_FALSE(is_builtin_scene("kitchen"));
  EXPECT_FALSE(is_builtin_scene(""));
}

TEST(BuiltinScenes, UnknownNameThrowsInputErrorListingKnownNames) {
  try {
    make_builtin_scene("kitchen");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("kitchen"), std::string::npos);
    for (const Minimum& m : kMinimums) EXPECT_NE(msg.find(m.name), std::string::npos) << msg;
  }
}

class BuiltinScene : public testing::TestWithParam<Minimum> {};

TEST_P(BuiltinScene, MeetsMinimumsAndIsWellFormed) {
  const Minimum& want = GetParam();
  Scene s = make_builtin_scene(want.name);
  EXPECT_EQ(s.name, want.name);
  EXPECT_GE(s.triangles.size(), want.triangles);
  EXPECT_GE(reflective_objects(s), want.reflectors);
  EXPECT_GE(s.camera_paths.size(), want.camera_paths);
  EXPECT_GE(s.cameras.size(), want.cameras);
  EXPECT_FALSE(s.area_lights.empty() && s.point_lights.empty());

  ASSERT_EQ(s.normals.size(), s.positions.size());
  ASSERT_EQ(s.uvs.size(), s.positions.size());
  ASSERT_EQ(s.triangle_material.size(), s.triangles.size());
  ASSERT_EQ(s.triangle_object.size(), s.triangles.size());
  for (size_t i = 0; i < s.positions.size(); ++i) {
    ASSERT_TRUE(is_finite(s.positions[i])) << i;
    ASSERT_NEAR(glm::length(s.normals[i]), 1.0f, 1e-4f) << i;
  }
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    ASSERT_LT(s.triangles[t].x, s.positions.size());
    ASSERT_LT(s.triangles[t].y, s.positions.size());
    ASSERT_LT(s.triangles[t].z, s.positions.size());
    ASSERT_LT(s.triangle_material[t], s.materials.size());
    ASSERT_LT(s.triangle_object[t], s.objects.size());
  }
  for (const Material& m : s.materials) {
    EXPECT_GE(m.specular, 0.0f);
    EXPECT_LE(m.specular, 1.0f);
    EXPECT_GE(m.gloss, 0.0f);
    EXPECT_LE(m.gloss, 1.0f);
    EXPECT_LT(m.diffuse_texture, int(s.textures.size()));
  }
  // Objects tile the triangle and vertex arrays in order, with unique names.
  uint32_t next_tri = 0, next_vert = 0;
  std::set<std::string> names;
  for (uint32_t o = 0; o < s.objects.size(); ++o) {
    const Object& obj = s.objects[o];
    EXPECT_TRUE(names.insert(obj.name).second) << "duplicate object name " << obj.name;
    EXPECT_EQ(obj.first_triangle, next_tri);
    EXPECT_EQ(obj.first_vertex, next_vert);
    EXPECT_GT(obj.triangle_count, 0u) << obj.name;
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
      ASSERT_EQ(s.triangle_object[t], o);
      for (int k = 0; k < 3; ++k) {
        ASSERT_GE(s.triangles[t][k], obj.first_vertex);
        ASSERT_LT(s.triangles[t][k], obj.first_vertex + obj.vertex_count);
      }
    }
    next_tri += obj.triangle_count;
    next_vert += obj.vertex_count;
  }
  EXPECT_EQ(next_tri, s.triangles.size());
  EXPECT_EQ(next_vert, s.positions.size());

  // Nothing for sanitize_scene to reject or drop (no zero-area triangles).
  Scene copy = s;
  EXPECT_NO_THROW(sanitize_scene(copy, want.name));
  EXPECT_EQ(copy.dropped_degenerate, 0u);
  EXPECT_EQ(copy.triangles.size(), s.triangles.size());

  // Cameras and camera paths sit inside the scene and can render.
  Bounds3 b = scene_bounds(s);
  for (const NamedCamera& c : s.cameras) {
    EXPECT_NO_THROW(validate_camera(c.camera, c.name.c_str()));
    EXPECT_EQ(c.camera.width, 512);
    EXPECT_EQ(c.camera.height, 512);
    if (want.cameras_inside && want.name != std::string("cornell")) {  // the Cornell box is open toward its camera
      EXPECT_TRUE(glm::all(glm::greaterThan(c.camera.position, b.min)) &&
                  glm::all(glm::lessThan(c.camera.position, b.max)))
          << c.name;
    }
  }
  std::set<std::string> path_names;
  for (const CameraPath& p : s.camera_paths) {
    EXPECT_TRUE(path_names.insert(p.name).second) << p.name;
    ASSERT_GE(p.keys.size(), 2u) << p.name;
    EXPECT_EQ(p.frames, 100);
    EXPECT_GE(p.keys.back().time - p.keys.front().time, 8.0f) << p.name;
    for (size_t k = 0; k < p.keys.size(); ++k) {
      if (k > 0) {
        EXPECT_GT(p.keys[k].time, p.keys[k - 1].time) << p.name;
      }
      vec3 pos = p.keys[k].position;
      EXPECT_TRUE(glm::all(glm::greaterThan(pos, b.min)) && glm::all(glm::lessThan(pos, b.max)))
          << p.name << " key " << k;
    }
  }
}

TEST_P(BuiltinScene, DeterministicBitForBit) {
  Scene a = make_builtin_scene(GetParam().name);
  Scene b = make_builtin_scene(GetParam().name);
  EXPECT_TRUE(same_bytes(a.positions, b.positions));
  EXPECT_TRUE(same_bytes(a.normals, b.normals));
  EXPECT_TRUE(same_bytes(a.uvs, b.uvs));
  EXPECT_TRUE(same_bytes(a.triangles, b.triangles));
  EXPECT_EQ(a.triangle_material, b.triangle_material);
  EXPECT_EQ(a.triangle_object, b.triangle_object);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].diffuse, b.materials[i].diffuse);
    EXPECT_EQ(a.materials[i].specular, b.materials[i].specular);
  }
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    EXPECT_EQ(a.cameras[i].camera.position, b.cameras[i].camera.position);
    EXPECT_EQ(a.cameras[i].camera.orientation, b.cameras[i].camera.orientation);
  }
}

INSTANTIATE_TEST_SUITE_P(Builtin, BuiltinScene, testing::ValuesIn(kMinimums),
                         [](const testing::TestParamInfo<Minimum>& param) {
                           std::string n = param.param.name;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

// The thesis' proportions: many triangles on reflectors, and both mirror (gloss 0) and
// glossy (gloss > 0) reflectors present.
TEST(BuiltinScenes, InteriorsMixMirrorAndGlossyReflectors) {
  for (const char* name : {"living-room", "bathroom"}) {
    Scene s = make_builtin_scene(name);
    bool mirror = false, glossy = false;
    for (uint32_t m : s.triangle_material) {
      const Material& mat = s.materials[m];
      if (mat.reflective() && mat.gloss == 0.0f) mirror = true;
      if (mat.reflective() && mat.gloss > 0.0f) glossy = true;
    }
    EXPECT_TRUE(mirror) << name;
    EXPECT_TRUE(glossy) << name;
    EXPECT_GT(reflective_triangles(s), s.triangles.size() / 3) << name;
  }
}

TEST(BuiltinScenes, CornellLayoutIsExact) {
  Scene s = make_builtin_scene("cornell");
  for (const char* name : {"floor", "ceiling", "back_wall", "left_wall", "right_wall",
                           "mirror_sphere", "glossy_block", "light"}) {
    EXPECT_NE(find_object(s, name), nullptr) << name;
  }
  ASSERT_EQ(s.objects.size(), 8u);
  Bounds3 b = scene_bounds(s);
  EXPECT_EQ(b.min, vec3(-1.0f, 0.0f, -1.0f));
  EXPECT_EQ(b.max, vec3(1.0f, 2.0f, 1.0f));

  // Walls: 8 × 8 quads each, flat at the stated coordinate, facing inward.
  struct Wall {
    const char* name;
    int axis;
    float value;
    vec3 normal;
    vec3 diffuse;
  };
  const Wall walls[] = {
      {"floor", 1, 0.0f, {0, 1, 0}, vec3(0.75f)},
      {"ceiling", 1, 2.0f, {0, -1, 0}, vec3(0.75f)},
      {"back_wall", 2, -1.0f, {0, 0, 1}, vec3(0.75f)},
      {"left_wall", 0, -1.0f, {1, 0, 0}, {0.75f, 0.1f, 0.1f}},
      {"right_wall", 0, 1.0f, {-1, 0, 0}, {0.1f, 0.75f, 0.1f}},
  };
  for (const Wall& w : walls) {
    const Object* o = find_object(s, w.name);
    ASSERT_NE(o, nullptr);
    EXPECT_EQ(o->triangle_count, 128u) << w.name;
    for (uint32_t v = o->first_vertex; v < o->first_vertex + o->vertex_count; ++v) {
      EXPECT_EQ(s.positions[v][w.axis], w.value) << w.name;
    }
    for (uint32_t t = o->first_triangle; t < o->first_triangle + o->triangle_count; ++t) {
      EXPECT_LT(glm::length(triangle_normal(s, t) - w.normal), 1e-6f) << w.name;
      EXPECT_EQ(s.materials[s.triangle_material[t]].diffuse, w.diffuse) << w.name;
      EXPECT_EQ(s.materials[s.triangle_material[t]].specular, 0.0f) << w.name;
    }
  }

  const Object* sphere = find_object(s, "mirror_sphere");
  ASSERT_NE(sphere, nullptr);
  EXPECT_EQ(sphere->triangle_count, 2u * 64u * 31u);
  for (uint32_t v = sphere->first_vertex; v < sphere->first_vertex + sphere->vertex_count; ++v) {
    EXPECT_NEAR(glm::length(s.positions[v] - vec3(-0.4f, 0.4f, -0.2f)), 0.4f, 1e-6f);
  }
  const Material& mirror = s.materials[s.triangle_material[sphere->first_triangle]];
  EXPECT_EQ(mirror.specular, 1.0f);
  EXPECT_EQ(mirror.gloss, 0.0f);
  EXPECT_EQ(mirror.diffuse, vec3(0.9f));

  const Object* block = find_object(s, "glossy_block");
  ASSERT_NE(block, nullptr);
  Bounds3 bb = object_bounds(s, uint32_t(block - s.objects.data()));
  EXPECT_NEAR(bb.min.y, 0.0f, 1e-6f);
  EXPECT_NEAR(bb.max.y, 1.0f, 1e-6f);
  EXPECT_LT(glm::length(bb.center() - vec3(0.45f, 0.5f, -0.35f)), 1e-5f);
  // Footprint of a 0.5 × 0.5 square turned 20°: half-width 0.25·(cos 20° + sin 20°).
  float half = 0.25f * (std::cos(glm::radians(20.0f)) + std::sin(glm::radians(20.0f)));
  EXPECT_NEAR(bb.extent().x, 2.0f * half, 1e-5f);
  EXPECT_NEAR(bb.extent().z, 2.0f * half, 1e-5f);
  const Material& glossy = s.materials[s.triangle_material[block->first_triangle]];
  EXPECT_EQ(glossy.diffuse, vec3(0.7f));
  EXPECT_EQ(glossy.specular, 0.5f);
  EXPECT_EQ(glossy.gloss, 0.3f);

  const Object* light = find_object(s, "light");
  ASSERT_NE(light, nullptr);
  for (uint32_t t = light->first_triangle; t < light->first_triangle + light->triangle_count; ++t) {
    EXPECT_EQ(triangle_normal(s, t), vec3(0, -1, 0));
    EXPECT_EQ(s.materials[s.triangle_material[t]].emission, vec3(12.0f));
    EXPECT_EQ(s.materials[s.triangle_material[t]].diffuse, vec3(0.0f));
  }
  Bounds3 lb = object_bounds(s, uint32_t(light - s.objects.data()));
  EXPECT_EQ(lb.min, vec3(-0.25f, 1.985f, -0.25f));
  EXPECT_EQ(lb.max, vec3(0.25f, 1.985f, 0.25f));

  ASSERT_EQ(s.area_lights.size(), 1u);
  const AreaLight& area = s.area_lights[0];
  EXPECT_EQ(area.corner, vec3(-0.25f, 1.98f, -0.25f));
  EXPECT_EQ(area.normal(), vec3(0, -1, 0));
  EXPECT_FLOAT_EQ(area.area(), 0.25f);
  EXPECT_EQ(area.radiance, vec3(12.0f));
  EXPECT_TRUE(s.point_lights.empty());
  EXPECT_EQ(s.ambient, vec3(0.03f));
  EXPECT_EQ(s.environment.color, vec3(0.0f));

  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].name, "front");
  const Camera& cam = s.cameras[0].camera;
  EXPECT_EQ(cam.position, vec3(0, 1, 3.5f));
  EXPECT_LT(glm::length(camera_forward(cam) - vec3(0, 0, -1)), 1e-6f);
  EXPECT_LT(glm::length(camera_up(cam) - vec3(0, 1, 0)), 1e-6f);
  EXPECT_EQ(cam.vfov_deg, 40.0f);
}

TEST(BuiltinScenes, RoomReflectorHasThePapersCylinder) {
  Scene s = make_builtin_scene("room-reflector");
  Bounds3 b = scene_bounds(s);
  EXPECT_EQ(b.min, vec3(-4, 0, -4));
  EXPECT_EQ(b.max, vec3(4, 4, 4));
  const Object* cyl = find_object(s, "reflector");
  ASSERT_NE(cyl, nullptr);
  EXPECT_EQ(cyl->triangle_count, 2176u);
  const Material& m = s.materials[s.triangle_material[cyl->first_triangle]];
  EXPECT_EQ(m.specular, 1.0f);
  EXPECT_EQ(m.gloss, 0.0f);
  Bounds3 cb = object_bounds(s, uint32_t(cyl - s.objects.data()));
  EXPECT_NEAR(cb.center().x, 0.0f, 1e-6f);
  EXPECT_NEAR(cb.center().z, 0.0f, 1e-6f);
  EXPECT_EQ(cb.min.y, 0.0f);
  EXPECT_EQ(reflective_objects(s), 1u);  // only the cylinder reflects, as in the paper
  EXPECT_FALSE(s.point_lights.empty());
  EXPECT_FALSE(s.area_lights.empty());
}

}  // namespace
}  // namespace proxima
