// Frame-level env-map reflections against the Embree reference (one mirror bounce): the
// rectified error is a fraction of plain env mapping's, layered maps follow the parallax
// between two viewpoints, only reflector pixels are shaded, any thread count agrees.
#include "proxima/reflect/envmap_reflection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "proxima/core/parallel.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/procedural.h"
#include "proxima/trace/reference_renderer.h"
#include "envmap_test_util.h"
#include "reflect_test_scenes.h"
#include "test_util.h"

namespace proxima {
namespace {

struct SceneFixture {
  Scene scene;
  std::unique_ptr<RayScene> rays;
  std::vector<uint32_t> reflectors;
  vec3 center;
  DistanceCubeMapOptions map_options;

  explicit SceneFixture(const std::string& name) : scene(make_builtin_scene(name)) {
    rays = std::make_unique<RayScene>(scene);
    reflectors = reflective_objects(scene);
    center = projection_center(scene, reflectors);
    map_options.resolution = 128;
    map_options.area_light_samples = 1;
    map_options.exclude = reflectors;
  }

  Camera camera(const std::string& name) const {
    for (const NamedCamera& c : scene.cameras)
      if (c.name == name) {
        Camera cam = c.camera;
        cam.width = 128;
        cam.height = 96;
        return cam;
      }
    ADD_FAILURE() << name;
    return {};
  }

  EnvmapInputs inputs(EnvmapMethod method) const {
    EnvmapInputs in;
    in.method = method;
    in.area_light_samples = 1;
    in.rectify.D = scene_bounds(scene).diagonal();
    return in;
  }

  ImageF reference(const Camera& cam) const {
    ReferenceOptions o;
    o.area_light_samples = 1;
    o.max_bounces = 1;
    return render_reference(scene, *rays, cam, o);
  }
};

using envmap_test::reflector_mae;

// The same reflector pixels shaded with 1 and with 2 threads (determinism checks).
std::pair<EnvmapFrame, EnvmapFrame> shade_at_one_and_two_threads(const SceneFixture& s, const Camera& cam,
                                                                 const ReflectorPixels& pixels,
                                                                 const EnvmapInputs& in) {
  std::pair<EnvmapFrame, EnvmapFrame> out;
  {
    ThreadLimit limit(1);
    out.first = shade_reflector_pixels(s.scene, *s.rays, cam, pixels, in);
  }
  {
    ThreadLimit limit(2);
    out.second = shade_reflector_pixels(s.scene, *s.rays, cam, pixels, in);
  }
  return out;
}

TEST(EnvmapReflection, RectifiedErrorIsAFractionOfPlainOnRoomReflector) {
  SceneFixture s("room-reflector");
  const Camera cam = s.camera("main");
  const DistanceCubeMap map = render_distance_cube_map(s.scene, *s.rays, s.center, s.map_options);
  const ReflectorPixels pixels = rasterize_reflector_pixels(s.scene, cam, s.reflectors);
  ASSERT_GT(pixels.count, 500u);
  const ImageF ref = s.reference(cam);
  EnvmapInputs plain = s.inputs(EnvmapMethod::Plain), rect = s.inputs(EnvmapMethod::Rectified);
  plain.map = rect.map = &map;
  const double e_plain =
      reflector_mae(shade_reflector_pixels(s.scene, *s.rays, cam, pixels, plain).color, ref, pixels);
  const EnvmapFrame r = shade_reflector_pixels(s.scene, *s.rays, cam, pixels, rect);
  const double e_rect = reflector_mae(r.color, ref, pixels);
  EXPECT_GT(e_plain, 0.01);
  EXPECT_LT(e_rect, e_plain / 3.0) << e_rect << " vs " << e_plain;
  EXPECT_EQ(r.stats.pixels, pixels.count);
  EXPECT_EQ(r.stats.lookups, pixels.count);  // a mirror: one lookup per pixel
  EXPECT_LE(r.stats.map_samples,
            pixels.count * size_t(rectify_step_limit(rect.rectify.D, rect.rectify.d_e) + 1));
}

TEST(EnvmapReflection, OnlyReflectorPixelsAreShadedAndThreadsAgree) {
  SceneFixture s("room-reflector");
  const Camera cam = s.camera("corner");
  const DistanceCubeMap map = render_distance_cube_map(s.scene, *s.rays, s.center, s.map_options);
  const ReflectorPixels pixels = rasterize_reflector_pixels(s.scene, cam, s.reflectors);
  EnvmapInputs in = s.inputs(EnvmapMethod::Rectified);
  in.map = &map;
  const auto [one, two] = shade_at_one_and_two_threads(s, cam, pixels, in);
  EXPECT_TRUE(one.color == two.color);
  size_t lit = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const bool any = one.color.at(x, y, 0) + one.color.at(x, y, 1) + one.color.at(x, y, 2) > 0.0f;
      if (pixels.triangle.at(x, y) == kNoTriangle) {
        ASSERT_FALSE(any) << x << "," << y;
      }
      lit += any;
    }
  EXPECT_GT(lit, pixels.count * 9 / 10);
}

TEST(EnvmapReflection, LayeredFollowsTheParallaxPlainMappingMisses) {
  SceneFixture s("room-parallax");
  const DistanceCubeMap map = render_distance_cube_map(s.scene, *s.rays, s.center, s.map_options);
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = viewer_radius(s.scene, s.reflectors, s.center);
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(s.scene, *s.rays, s.center, s.map_options, lo);
  ASSERT_GE(layers.size(), 2u);  // the room behind the sphere
  ASSERT_LE(layers.size(), 3u);
  for (const char* view : {"left", "right"}) {
    const Camera cam = s.camera(view);
    const ReflectorPixels pixels = rasterize_reflector_pixels(s.scene, cam, s.reflectors);
    const ImageF ref = s.reference(cam);
    EnvmapInputs plain = s.inputs(EnvmapMethod::Plain), rect = s.inputs(EnvmapMethod::Rectified),
                 layered = s.inputs(EnvmapMethod::Layered);
    plain.map = rect.map = &map;
    layered.layers = layers;
    const double e_plain =
        reflector_mae(shade_reflector_pixels(s.scene, *s.rays, cam, pixels, plain).color, ref, pixels);
    const double e_rect =
        reflector_mae(shade_reflector_pixels(s.scene, *s.rays, cam, pixels, rect).color, ref, pixels);
    const double e_layered =
        reflector_mae(shade_reflector_pixels(s.scene, *s.rays, cam, pixels, layered).color, ref, pixels);
    EXPECT_LT(e_layered, e_plain / 2.0) << view << ": " << e_layered << " vs " << e_plain;
    EXPECT_LE(e_layered, e_rect) << view << ": " << e_layered << " vs rectified " << e_rect;
  }
}

TEST(EnvmapReflection, LayeredIsTheSameForAnyThreadCount) {
  SceneFixture s("room-parallax");
  DistanceCubeLayerOptions lo;
  lo.viewer_radius = viewer_radius(s.scene, s.reflectors, s.center);
  const std::vector<DistanceCubeMap> layers = render_distance_cube_layers(s.scene, *s.rays, s.center, s.map_options, lo);
  const Camera cam = s.camera("left");
  const ReflectorPixels pixels = rasterize_reflector_pixels(s.scene, cam, s.reflectors);
  EnvmapInputs in = s.inputs(EnvmapMethod::Layered);
  in.layers = layers;
  const auto [one, two] = shade_at_one_and_two_threads(s, cam, pixels, in);
  EXPECT_TRUE(one.color == two.color);
  EXPECT_TRUE(one.object == two.object);
  EXPECT_EQ(one.stats.map_samples, two.stats.map_samples);
}

TEST(EnvmapReflection, GlossyLobeFollowsTheReferenceSamples) {
  // A glossy sphere far from six flat-colored walls (ambient light only: texel = albedo):
  // plain env mapping is exact up to the texel grid, so with the reference's lobe samples
  // the images agree closely; other lobe samples would differ by the lobe's noise.
  Scene scene = reflect_test::box_room({-200, -200, -200}, {200, 200, 200});
  scene.point_lights.clear();
  scene.ambient = vec3(1.0f);
  Material glossy;
  glossy.diffuse = vec3(0.5f);
  glossy.specular = 0.8f;
  glossy.gloss = 0.6f;
  const uint32_t ball = add_object(scene, make_sphere(0.5f, 48, 24), "ball", add_material(scene, glossy));
  RayScene rays(scene);
  const uint32_t reflectors[] = {ball};
  DistanceCubeMapOptions mo;
  mo.resolution = 128;
  mo.area_light_samples = 1;
  mo.exclude = reflectors;
  const DistanceCubeMap map = render_distance_cube_map(scene, rays, vec3(0.0f), mo);
  Camera cam = look_at({0.3f, 0.4f, 2.0f}, vec3(0.0f), {0, 1, 0}, 40.0f, 64, 64);
  const ReflectorPixels pixels = rasterize_reflector_pixels(scene, cam, reflectors);
  ASSERT_GT(pixels.count, 1000u);
  ReferenceOptions ro;
  ro.max_bounces = 1;
  ro.glossy_rays = 9;
  ro.seed = 5;
  const ImageF ref = render_reference(scene, rays, cam, ro);
  EnvmapInputs in;
  in.method = EnvmapMethod::Plain;
  in.map = &map;
  in.glossy_rays = 9;
  in.seed = 5;
  const EnvmapFrame same = shade_reflector_pixels(scene, rays, cam, pixels, in);
  in.seed = 6;  // other lobe samples
  const EnvmapFrame other = shade_reflector_pixels(scene, rays, cam, pixels, in);
  const double e_same = reflector_mae(same.color, ref, pixels);
  const double e_other = reflector_mae(other.color, ref, pixels);
  EXPECT_EQ(same.stats.lookups, 9 * pixels.count);
  EXPECT_LT(e_same, 0.002);
  EXPECT_GT(e_other, 5.0 * e_same) << e_same << " vs " << e_other;
}

TEST(EnvmapReflection, MethodNamesParseBackAndUnknownNamesAreRefused) {
  for (EnvmapMethod m : {EnvmapMethod::Plain, EnvmapMethod::Rectified, EnvmapMethod::Average, EnvmapMethod::Layered,
                         EnvmapMethod::BoxProbe})
    EXPECT_EQ(parse_envmap_method(envmap_method_name(m)), m) << envmap_method_name(m);
  const std::string message = error_of([] { parse_envmap_method("mirror", "--method"); });
  EXPECT_EQ(message, "--method: unknown env-map method 'mirror' (envmap, rectified, average, layered, boxprobe)");
  EXPECT_NE(error_of([] { parse_envmap_method("reference"); }), "");  // the reference is not a lookup
}

}  // namespace
}  // namespace proxima
