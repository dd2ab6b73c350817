// Box-projected cube maps: exact where the environment is the proxy box itself (a mirror
// inside an empty box room), the ray–box exit point, and the scene file's probe_box.
#include "proxima/reflect/box_probe.h"

#include <gtest/gtest.h>

#include "proxima/eval/image_error.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/scene/scene_file.h"
#include "proxima/trace/reference_renderer.h"
#include "reflect_test_scenes.h"
#include "test_util.h"

namespace proxima {
namespace {

using reflect_test::add_diffuse;
using reflect_test::add_quad;
using reflect_test::box_room;

TEST(BoxProbe, ExitPointOfARayInsideAndOutsideTheBox) {
  const Bounds3 box{vec3(-1.0f), vec3(1.0f)};
  const std::optional<vec3> a = box_exit_point(box, vec3(0.0f), vec3(1, 0, 0));
  ASSERT_TRUE(a);
  EXPECT_FLOAT_EQ(a->x, 1.0f);
  const std::optional<vec3> b = box_exit_point(box, vec3(0.5f, 0.0f, 0.0f), glm::normalize(vec3(-1, 1, 0)));
  ASSERT_TRUE(b);
  EXPECT_NEAR(b->x, -0.5f, 1e-6f);
  EXPECT_NEAR(b->y, 1.0f, 1e-6f);
  EXPECT_TRUE(box_exit_point(box, vec3(3, 0, 0), vec3(-1, 0, 0)));   // enters, then leaves at x = −1
  EXPECT_FALSE(box_exit_point(box, vec3(3, 0, 0), vec3(1, 0, 0)));   // moving away
  EXPECT_FALSE(box_exit_point(box, vec3(0, 3, 0), vec3(1, 0, 0)));   // parallel, outside the slab
  EXPECT_FALSE(box_exit_point(box, vec3(0.0f), vec3(0.0f)));
}

// A mirror quad inside an empty inward-facing box room whose walls are the proxy box: every
// reflected ray ends on the box, so the lookup is exact up to the texel filter, while plain
// env mapping (no parallax) is far off.
TEST(BoxProbe, ExactForAMirrorInsideAnEmptyBoxRoom) {
  Scene scene = box_room(vec3(-2, 0, -3), vec3(2, 2.5f, 3));
  Material mirror;
  mirror.name = "mirror";
  mirror.diffuse = vec3(0.0f);
  mirror.specular = 1.0f;
  const uint32_t m = add_material(scene, mirror);
  add_quad(scene, vec3(-1.0f, 0.3f, -1.5f), vec3(2, 0, 0), vec3(0, 1.6f, 0), m, "mirror");
  scene.point_lights[0].position = vec3(0.3f, 2.0f, 1.0f);
  const RayScene rays(scene);
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  ASSERT_EQ(reflectors.size(), 1u);
  EXPECT_EQ(probe_proxy_box(scene).min, vec3(-2, 0, -3));  // no probe_box: the scene's bounds
  EXPECT_EQ(probe_proxy_box(scene).max, vec3(2, 2.5f, 3));
  DistanceCubeMapOptions mo;
  mo.resolution = 256;
  mo.area_light_samples = 1;
  mo.exclude = reflectors;
  const DistanceCubeMap map = render_distance_cube_map(scene, rays, projection_center(scene, reflectors), mo);
  const Camera cam = look_at(vec3(0.8f, 1.4f, 2.5f), vec3(0.0f, 1.1f, -1.5f), vec3(0, 1, 0), 60.0f, 160, 120);
  const ReflectorPixels pixels = rasterize_reflector_pixels(scene, cam, reflectors);
  ASSERT_GT(pixels.count, 1500u);
  ReferenceOptions ro;
  ro.area_light_samples = 1;
  ro.max_bounces = 1;
  const ImageF reference = render_reference(scene, rays, cam, ro);
  ImageU8 mask(cam.width, cam.height, 1, 0);
  for (size_t i = 0; i < mask.data().size(); ++i) mask.data()[i] = pixels.triangle.data()[i] != kNoTriangle;
  auto mae = [&](EnvmapMethod method) {
    EnvmapInputs in;
    in.method = method;
    in.map = &map;
    in.box = probe_proxy_box(scene);
    in.area_light_samples = 1;
    const EnvmapFrame f = shade_reflector_pixels(scene, rays, cam, pixels, in);
    EXPECT_EQ(f.stats.edge_lookups, 0u);
    return compare_images(f.color, reference, &mask).mae_avg;
  };
  const double box = mae(EnvmapMethod::BoxProbe), plain = mae(EnvmapMethod::Plain);
  RecordProperty("boxprobe_mae", std::to_string(box));
  RecordProperty("plain_mae", std::to_string(plain));
  EXPECT_LT(box, 0.5) << "0–255 display scale";
  EXPECT_GT(plain, 20.0 * box) << plain << " vs " << box;
}

TEST(BoxProbe, SceneFileProbeBoxIsReadAndBadBoxesAreRefusedNamingTheFile) {
  TempDir dir;
  const std::string head = R"({"builtin": "room-reflector", )";
  write_file(dir.path / "good.json", head + R"("probe_box": {"min": [-1, 0, -2], "max": [1, 3, 2]}})");
  const Scene s = load_scene_file(dir.path / "good.json");
  EXPECT_EQ(s.probe_box.min, vec3(-1, 0, -2));
  EXPECT_EQ(probe_proxy_box(s).max, vec3(1, 3, 2));
  const std::pair<const char*, const char*> bad[] = {
      {R"({"min": [1, 0, -2], "max": [1, 3, 2]})", "min must be below max"},
      {R"({"min": [0, 0], "max": [1, 3, 2]})", "must have 3 elements"},
      {R"({"max": [1, 3, 2]})", "missing required key 'min'"},
      {R"({"min": [0, 0, 0], "max": [1, 1, 1], "size": 2})", "unknown key"},
      {R"([0, 1])", "must be an object"}};
  for (const auto& [box, expected] : bad) {
    write_file(dir.path / "bad.json", head + R"("probe_box": )" + box + "}");
    const std::string message = error_of([&] { load_scene_file(dir.path / "bad.json"); });
    EXPECT_NE(message.find((dir.path / "bad.json").string()), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace proxima
