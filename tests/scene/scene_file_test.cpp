#include "proxima/scene/scene_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

// Restores the working directory on scope exit.
struct ScopedCwd {
  fs::path saved = fs::current_path();
  explicit ScopedCwd(const fs::path& p) { fs::current_path(p); }
  ~ScopedCwd() { fs::current_path(saved); }
};

// The error a scene file with this text raises.
std::string scene_error(const std::string& json) {
  TempDir dir;
  write_file(dir.path / "scene.json", json);
  return error_of([&] { load_scene_file(dir.path / "scene.json"); });
}

const char* kTriangleObj = "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl from_file\nf 1 2 3\n";
const char* kTriangleMtl = "newmtl from_file\nKd 0.1 0.2 0.3\n";

const char* kFullScene = R"({
  // comments are allowed
  "name": "demo",
  "materials": [
    {"name": "red", "diffuse": [0.8, 0.1, 0.1]},
    {"name": "mirror", "diffuse": 0.1, "specular": 1, "gloss": 0.05},
    {"name": "glow", "emission": [4, 4, 3]}
  ],
  "objects": [
    {"type": "mesh", "name": "tri", "file": "meshes/tri.obj",
     "transform": {"translate": [10, 0, 0], "rotate_deg": [0, 90, 0], "scale": 2}},
    {"type": "mesh", "file": "meshes/tri.obj", "material_overrides": {"from_file": "mirror"}},
    {"type": "sphere", "name": "ball", "radius": 0.5, "segments": 16, "rings": 8,
     "material": "mirror", "transform": {"translate": [0, 1, 0]},
     "animation": {"keys": [{"time": 0}, {"time": 2, "translate": [1, 0, 0], "rotate_deg": [0, 45, 0]}]}},
    {"type": "box", "size": [1, 2, 3], "material": "red"},
    {"type": "plane", "size": [4, 4], "subdivisions": [2, 2], "material": "red"},
    {"type": "cylinder", "radius": 0.25, "height": 1, "capped": false},
    {"type": "torus", "major_radius": 1, "minor_radius": 0.2},
    {"type": "teapot", "tessellation": 4, "material": "glow"}
  ],
  "cameras": [
    {"name": "front", "position": [0, 1, 5], "target": [0, 1, 0], "vfov_deg": 45},
    {"position": [5, 5, 5], "target": [0, 0, 0], "near": 0.1, "far": 50}
  ],
  "camera_paths": [
    {"name": "orbit", "frames": 24, "keys": [
      {"time": 0, "position": [0, 1, 5], "target": [0, 0, 0]},
      {"time": 1, "position": [5, 1, 0], "target": [0, 0, 0], "vfov_deg": 50}]}
  ],
  "lights": [
    {"type": "point", "position": [0, 3, 0], "intensity": [10, 10, 10]},
    {"type": "area", "corner": [-0.5, 2.9, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
     "radiance": 5}
  ],
  "environment": {"color": [0.1, 0.2, 0.3]},
  "ambient": [0.01, 0.01, 0.01]
})";

TEST(SceneFileTest, FullSceneResolvesPathsRelativeToTheFile) {
  TempDir dir;
  write_file(dir.path / "scenes" / "meshes" / "tri.obj", kTriangleObj);
  write_file(dir.path / "scenes" / "meshes" / "tri.mtl", kTriangleMtl);
  write_file(dir.path / "scenes" / "scene.json", kFullScene);
  fs::create_directories(dir.path / "elsewhere");
  const ScopedCwd cwd(dir.path / "elsewhere");

  const Scene s = load_scene_file(fs::path("..") / "scenes" / "scene.json");
  EXPECT_EQ(s.name, "demo");
  ASSERT_EQ(s.objects.size(), 8u);
  EXPECT_EQ(s.objects[0].name, "tri");
  EXPECT_EQ(s.objects[2].name, "ball");

  // Object 0: scale 2, then 90° about Y (+X → −Z), then +10 in X.
  const uvec3 t0 = s.triangles[s.objects[0].first_triangle];
  EXPECT_NEAR(glm::distance(s.positions[t0.x], vec3(10, 0, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(s.positions[t0.y], vec3(10, 0, -2)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(s.positions[t0.z], vec3(10, 2, 0)), 0.0f, 1e-5f);

  // Materials: the file's own for object 0, the override for object 1.
  const Material& own = s.materials[s.triangle_material[s.objects[0].first_triangle]];
  EXPECT_EQ(own.name, "from_file");
  EXPECT_NEAR(own.diffuse.z, 0.3f, 1e-6f);
  EXPECT_EQ(s.materials[s.triangle_material[s.objects[1].first_triangle]].name, "mirror");
  const Material& mirror = s.materials[s.triangle_material[s.objects[2].first_triangle]];
  EXPECT_EQ(mirror.name, "mirror");
  EXPECT_EQ(mirror.specular, 1.0f);
  EXPECT_FLOAT_EQ(mirror.gloss, 0.05f);
  EXPECT_EQ(mirror.diffuse, vec3(0.1f));
  EXPECT_EQ(s.materials[s.triangle_material[s.objects[5].first_triangle]].name, "default");

  // The sphere sits at y = 1 with radius 0.5; its animation pivots on its center.
  const Bounds3 ball = object_bounds(s, 2);
  EXPECT_NEAR(ball.center().y, 1.0f, 1e-5f);
  EXPECT_NEAR(ball.extent().y, 1.0f, 1e-5f);
  ASSERT_EQ(s.objects[2].animation.keys.size(), 2u);
  EXPECT_EQ(s.objects[2].animation.pivot, vec3(0, 1, 0));
  EXPECT_EQ(s.objects[2].animation.keys[1].translation, vec3(1, 0, 0));
  EXPECT_NEAR(glm::angle(s.objects[2].animation.keys[1].rotation), glm::radians(45.0f), 1e-5f);
  const Bounds3 box = object_bounds(s, 3);
  EXPECT_NEAR(glm::distance(box.extent(), vec3(1, 2, 3)), 0.0f, 1e-5f);

  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_EQ(s.cameras[0].name, "front");
  EXPECT_EQ(s.cameras[1].name, "camera1");
  EXPECT_FLOAT_EQ(s.cameras[0].camera.vfov_deg, 45.0f);
  EXPECT_NEAR(glm::distance(camera_forward(s.cameras[0].camera), vec3(0, 0, -1)), 0.0f, 1e-5f);
  EXPECT_FLOAT_EQ(s.cameras[1].camera.far, 50.0f);

  ASSERT_EQ(s.camera_paths.size(), 1u);
  EXPECT_EQ(s.camera_paths[0].frames, 24);
  ASSERT_EQ(s.camera_paths[0].keys.size(), 2u);
  EXPECT_FLOAT_EQ(s.camera_paths[0].keys[1].vfov_deg, 50.0f);

  ASSERT_EQ(s.point_lights.size(), 1u);
  EXPECT_EQ(s.point_lights[0].intensity, vec3(10.0f));
  ASSERT_EQ(s.area_lights.size(), 1u);
  EXPECT_EQ(s.area_lights[0].radiance, vec3(5.0f));
  EXPECT_EQ(s.environment.color, vec3(0.1f, 0.2f, 0.3f));
  EXPECT_FALSE(s.environment.has_cube_map());
  EXPECT_EQ(s.ambient, vec3(0.01f));
}

TEST(SceneFileTest, CubeEnvironmentFromSixFaces) {
  TempDir dir;
  const char* faces[] = {"px", "nx", "py", "ny", "pz", "nz"};
  for (int f = 0; f < 6; ++f) write_png_linear(dir.path / (std::string(faces[f]) + ".png"), ImageF(4, 4, 3, 0.25f));
  write_png_linear(dir.path / "wide.png", ImageF(8, 4, 3, 0.25f));
  const std::string objects = R"("objects": [{"type": "sphere", "radius": 1}])";
  write_file(dir.path / "env.json", "{" + objects + R"(, "environment": {"cube":
      ["px.png", "nx.png", "py.png", "ny.png", "pz.png", "nz.png"]}})");
  const Scene s = load_scene_file(dir.path / "env.json");
  ASSERT_TRUE(s.environment.has_cube_map());
  EXPECT_EQ(s.environment.cube[5].width(), 4);
  EXPECT_EQ(s.environment.cube[5].channels(), 3);

  write_file(dir.path / "bad_env.json", "{" + objects + R"(, "environment": {"cube":
      ["px.png", "nx.png", "py.png", "ny.png", "pz.png", "wide.png"]}})");
  const std::string msg = error_of([&] { load_scene_file(dir.path / "bad_env.json"); });
  EXPECT_NE(msg.find("bad_env.json: environment.cube[5]: face is 8x4"), std::string::npos) << msg;
}

TEST(SceneFileTest, MissingFile) {
  TempDir dir;
  const std::string msg = error_of([&] { load_scene_file(dir.path / "nope.json"); });
  EXPECT_NE(msg.find("nope.json"), std::string::npos) << msg;
}

TEST(SceneFileTest, MalformedJsonNamesLineAndColumn) {
  const std::string msg = scene_error("{\n  \"objects\": [\n    {\"type\": \"sphere\",}\n  ]\n}\n");
  EXPECT_NE(msg.find("scene.json: JSON parse error at line 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("column"), std::string::npos) << msg;
}

TEST(SceneFileTest, TopLevelMustBeAnObject) {
  EXPECT_NE(scene_error("[1, 2]").find("scene.json: top level: must be an object"), std::string::npos);
}

TEST(SceneFileTest, UnknownKeyIsNamed) {
  const std::string msg = scene_error(R"({"objects": [{"type": "sphere", "raduis": 1}]})");
  EXPECT_NE(msg.find("scene.json: objects[0].raduis: unknown key"), std::string::npos) << msg;
  EXPECT_NE(scene_error(R"({"object": []})").find("scene.json: object: unknown key"), std::string::npos);
}

TEST(SceneFileTest, BadValuesAreNamedWithTheirPath) {
  const std::string sphere = R"({"type": "sphere", "radius": 1})";
  struct Case {
    std::string json, expected;
  };
  const Case cases[] = {
      {R"({"objects": [)" + sphere + R"(, {"type": "sphere", "radius": -1}]})",
       "objects[1].radius: must be > 0"},
      {R"({"objects": [{"type": "sphere", "radius": "big"}]})", "objects[0].radius: must be a number, not string"},
      {R"({"objects": [{"type": "sphere", "radius": 1e39}]})", "objects[0].radius: must be a finite number"},
      {R"({"objects": [{"type": "sphere"}]})", "objects[0]: missing required key 'radius'"},
      {R"({"objects": [{"type": "cone"}]})", "objects[0].type: unknown object type 'cone'"},
      {R"({"objects": [{"type": "sphere", "radius": 1, "segments": 2.5}]})", "objects[0].segments: must be an integer"},
      {R"({"objects": [{"type": "box", "size": [1, 0, 1]}]})", "objects[0].size: sizes must be > 0"},
      {R"({"objects": [{"type": "sphere", "radius": 1, "transform": {"scale": [1, 0, 1]}}]})",
       "objects[0].transform.scale: scale factors must be non-zero"},
      {R"({"materials": [{"name": "m", "specular": 2}], "objects": [)" + sphere + "]}",
       "materials[0].specular: must be in [0, 1]"},
      {R"({"materials": [{"name": "m", "diffuse": [1, -1, 0]}], "objects": [)" + sphere + "]}",
       "materials[0].diffuse[1]: must be >= 0"},
      {R"({"materials": [{"name": "m"}, {"name": "m"}], "objects": [)" + sphere + "]}",
       "materials[1].name: duplicate material name 'm'"},
      {R"({"objects": [)" + sphere + R"(], "cameras": [{"position": [0, 0, 0], "target": [0, 0, 0]}]})",
       "cameras[0].target: must differ from position"},
      {R"({"objects": [)" + sphere + R"(], "cameras": [{"position": [0, 0, 1], "target": [0, 0, 0], "vfov_deg": 180}]})",
       "cameras[0].vfov_deg: must be in (0, 180) degrees"},
      {R"({"objects": [)" + sphere + R"(], "cameras": [{"position": [0, 5, 0], "target": [0, 0, 0]}]})",
       "cameras[0]: up must not be zero or parallel"},
      {R"({"objects": [)" + sphere + R"(], "cameras": [{"position": [0, 0, 1], "target": [0, 0, 0], "near": 2, "far": 1}]})",
       "cameras[0].far: must be > near"},
      {R"({"objects": [)" + sphere + R"(], "camera_paths": [{"keys": [
          {"time": 1, "position": [0, 0, 1], "target": [0, 0, 0]},
          {"time": 1, "position": [0, 0, 2], "target": [0, 0, 0]}]}]})",
       "camera_paths[0].keys[1].time: key times must increase strictly"},
      {R"({"objects": [)" + sphere + R"(], "camera_paths": [{"keys": []}]})",
       "camera_paths[0].keys: must have at least one key"},
      {R"({"objects": [)" + sphere + R"(], "lights": [{"type": "spot"}]})", "lights[0].type: unknown light type 'spot'"},
      {R"({"objects": [)" + sphere + R"(], "lights": [{"type": "area", "corner": [0, 0, 0],
          "edge_u": [1, 0, 0], "edge_v": [2, 0, 0], "radiance": 1}]})",
       "lights[0]: edge_u and edge_v must span a rectangle of area > 0"},
      {R"({"objects": [)" + sphere + R"(], "lights": [{"type": "point", "position": [0, 0], "intensity": 1}]})",
       "lights[0].position: must have 3 elements, not 2"},
      {R"({"objects": [)" + sphere + R"(], "environment": {"cube": ["a.png"]}})",
       "environment.cube: must have 6 elements, not 1"},
      {R"({"objects": [)" + sphere + R"(], "builtin": "atlantis"})", "builtin: unknown built-in scene 'atlantis'"},
      {R"({"materials": []})", "top level: the scene has no geometry"},
  };
  for (const Case& c : cases) {
    const std::string msg = scene_error(c.json);
    EXPECT_NE(msg.find("scene.json: " + c.expected), std::string::npos)
        << "expected: " << c.expected << "\n     got: " << msg;
  }
}

TEST(SceneFileTest, UnknownMaterialIsNamed) {
  const std::string msg =
      scene_error(R"({"objects": [{"type": "sphere", "radius": 1, "material": "gold"}]})");
  EXPECT_NE(msg.find("scene.json: objects[0].material: unknown material 'gold'"), std::string::npos) << msg;
}

TEST(SceneFileTest, MeshProblemsNameSceneAndMeshFile) {
  TempDir dir;
  write_file(dir.path / "tri.obj", kTriangleObj);
  write_file(dir.path / "tri.mtl", kTriangleMtl);
  write_file(dir.path / "a.json", R"({"objects": [{"type": "mesh", "file": "gone.obj"}]})");
  std::string msg = error_of([&] { load_scene_file(dir.path / "a.json"); });
  EXPECT_NE(msg.find("a.json: objects[0].file: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("gone.obj: no such file"), std::string::npos) << msg;

  write_file(dir.path / "b.json",
             R"({"objects": [{"type": "mesh", "file": "tri.obj", "material_overrides": {"steel": "x"}}]})");
  msg = error_of([&] { load_scene_file(dir.path / "b.json"); });
  EXPECT_NE(msg.find("b.json: objects[0].material_overrides.steel: no material named 'steel'"),
            std::string::npos)
      << msg;
}

}  // namespace
}  // namespace proxima
