// The soft-shadow study (study/shadows.h) on a small table scene: occluders reconstructed
// from every sampling cast the geometry's shadow within a bound, shadow maps of the
// geometry agree with Embree rays, the geometry is exact against itself, metric names and
// prefixes, images only with an output directory, the same figures and files for 1 and 2
// threads, validation naming the flag.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "proxima/core/parallel.h"
#include "proxima/scene/procedural.h"
#include "proxima/study/shadows.h"
#include "study_test_util.h"
#include "test_util.h"

namespace proxima {
namespace {

// Ground 4×4 m at y = 0, a 1.2×1.2 m table top floating 0.6 m above it (a wide penumbra)
// and a 0.4 m cube on the ground, a point light 3 m up (where the area light centres), one
// camera looking down at them.
Scene table_scene() {
  Scene s;
  s.name = "table";
  Material m;
  m.diffuse = vec3(0.5f);
  const uint32_t mat = add_material(s, m);
  add_object(s, make_plane(4.0f, 4.0f, 1, 1), "ground", mat);
  Mesh top = make_box(vec3(1.2f, 0.05f, 1.2f), 1);
  transform_mesh(top, glm::translate(mat4(1.0f), vec3(-0.3f, 0.6f, 0.0f)));
  add_object(s, top, "table", mat);
  Mesh cube = make_box(vec3(0.4f), 1);
  transform_mesh(cube, glm::translate(mat4(1.0f), vec3(1.0f, 0.2f, 0.6f)));
  add_object(s, cube, "cube", mat);
  s.point_lights.push_back(PointLight{vec3(0, 3, 0), vec3(10)});
  s.cameras.push_back({"main", look_at(vec3(0, 4.0f, 3.0f), vec3(0), vec3(0, 1, 0), 60.0f, 64, 64, 0.05f, 50.0f)});
  return s;
}

study::ShadowsOptions small_options() {
  study::ShadowsOptions o;
  o.samplings = {ShadowSampling::Nrr, ShadowSampling::Conventional, ShadowSampling::Peeling, ShadowSampling::Geometry};
  o.light_size = 0.3f;
  o.light_samples = 4;
  o.ref_res = 128;
  o.out_res = 64;
  o.shadow_res = 256;
  return o;
}

TEST(ShadowsStudy, ReconstructedOccludersCastTheGeometrysShadow) {
  const Scene scene = table_scene();
  const Results r = study::run_shadows(scene, small_options(), {});
  const auto& m = r.metrics;
  EXPECT_EQ(m.at("light_samples"), 16.0);
  // Of 64² pixels: the ground fills part of the view, the background the rest.
  EXPECT_GT(m.at("receivers"), 1000.0);
  EXPECT_LT(m.at("receivers"), 64.0 * 64.0);
  // Shadow mapping itself (resolution, bias) against exact rays: aliasing at edges only.
  EXPECT_LT(m.at("geometry_vs_rays_visibility_error_mean"), 4.0);
  EXPECT_EQ(m.at("geometry_visibility_error_max"), 0.0);  // the ground truth against itself
  EXPECT_EQ(m.at("geometry_occluder_triangles"), double(scene.triangles.size()));
  for (const char* sampling : {"nrr", "conventional", "peeling"}) {
    const std::string p = std::string(sampling) + "_";
    EXPECT_LT(m.at(p + "visibility_error_mean"), 5.0) << sampling;  // of 255
    EXPECT_LT(m.at(p + "visibility_error_rays_mean"), 5.0) << sampling;
    EXPECT_LE(m.at(p + "intensity_error_mean"), m.at(p + "visibility_error_mean")) << sampling;
    EXPECT_LE(m.at(p + "intensity_error_max"), m.at(p + "visibility_error_max")) << sampling;
    EXPECT_GT(m.at(p + "reference_samples"), 1000.0) << sampling;
    EXPECT_GT(m.at(p + "occluder_triangles"), 0.0) << sampling;
  }
  ASSERT_EQ(r.tables.size(), 3u);     // vs geometry, vs rays, times
  EXPECT_EQ(r.tables[0].rows.size(), 4u);  // one row per sampling
  EXPECT_EQ(r.tables[1].rows.size(), 5u);  // and the geometry's shadow maps vs rays
  EXPECT_TRUE(r.images.empty());           // no output directory
}

TEST(ShadowsStudy, OneSamplingHasNoPrefixAndNoRaysNoRayMetrics) {
  study::ShadowsOptions o = small_options();
  o.samplings = {ShadowSampling::Nrr};
  o.no_rays = true;
  o.ref_res = 64;
  const Results r = study::run_shadows(table_scene(), o, {});
  EXPECT_TRUE(r.metrics.count("visibility_error_mean"));
  EXPECT_FALSE(r.metrics.count("nrr_visibility_error_mean"));
  for (const auto& [name, value] : r.metrics) EXPECT_EQ(name.find("rays"), std::string::npos) << name;
  EXPECT_EQ(r.tables.size(), 2u);
}

TEST(ShadowsStudy, SameFiguresAndImagesForOneAndTwoThreads) {
  const Scene scene = table_scene();
  study::ShadowsOptions o = small_options();
  o.samplings = {ShadowSampling::Nrr, ShadowSampling::Peeling};
  o.ref_res = 64;
  o.shadow_res = 128;
  TempDir one_dir, two_dir;
  Results one, two;
  {
    ThreadLimit limit(1);
    one = study::run_shadows(scene, o, {one_dir.path});
  }
  {
    ThreadLimit limit(2);
    two = study::run_shadows(scene, o, {two_dir.path});
  }
  ASSERT_EQ(one.metrics.size(), two.metrics.size());
  for (const auto& [name, value] : one.metrics)
    if (name.find("_ms") == std::string::npos) {
      EXPECT_EQ(value, two.metrics.at(name)) << name;
    }
  // geometry_shadow, rays_shadow, and per sampling _shadow and _error.
  EXPECT_EQ(one.images.size(), 6u);
  ASSERT_EQ(one.images, two.images);
  for (const auto& [role, file] : one.images) {
    EXPECT_TRUE(std::filesystem::is_regular_file(one_dir.path / file)) << file;
    EXPECT_EQ(file_bytes(one_dir.path / file), file_bytes(two_dir.path / file)) << file;
  }
}

TEST(ShadowsStudy, ValidateNamesTheFlag) {
  const std::pair<void (*)(study::ShadowsOptions&), const char*> cases[] = {
      {[](study::ShadowsOptions& o) { o.light_size = 0.0f; }, "--light-size"},
      {[](study::ShadowsOptions& o) { o.light_size = std::nanf(""); }, "--light-size"},
      {[](study::ShadowsOptions& o) { o.light_samples = 65; }, "--light-samples"},
      {[](study::ShadowsOptions& o) { o.ref_res = 7; }, "--ref-res"},
      {[](study::ShadowsOptions& o) { o.out_res = kMaxImageSide + 1; }, "--out-res"},
      {[](study::ShadowsOptions& o) { o.shadow_res = 0; }, "--shadow-res"},
      {[](study::ShadowsOptions& o) { o.shadow_footprint = 16.5f; }, "--shadow-footprint"},
      {[](study::ShadowsOptions& o) { o.shadow_footprint = -1.0f; }, "--shadow-footprint"},
      {[](study::ShadowsOptions& o) { o.samplings.clear(); }, "--sampling"},
  };
  for (const auto& [change, flag] : cases) {
    study::ShadowsOptions o;
    change(o);
    const std::string error = error_of([&] { study::validate(o); });
    EXPECT_EQ(error.rfind(flag, 0), 0u) << flag << ": " << error;
  }
  study::ShadowsOptions o;
  o.out_res = kMaxImageSide;
  EXPECT_EQ(error_of([&] { study::validate(o); }), "");  // every image side up to kMaxImageSide
  o = {};
  o.camera.path = "nowhere";
  EXPECT_EQ(error_of([&] { study::validate(o, table_scene()); }).rfind("--path", 0), 0u);
}

}  // namespace
}  // namespace proxima
