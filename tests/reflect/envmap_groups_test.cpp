// Env maps per group of reflectors (envmap_groups.h): reflectors far apart get a map each and
// a smaller rectified error than from one shared map; reflectors close together share one;
// the number of maps is bounded; the grouping is deterministic.
#include "proxima/reflect/envmap_groups.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/reflect/envmap_frame_reflections.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/reflect/envmap_set.h"
#include "proxima/reflect/hit_shading.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/scene/procedural.h"
#include "proxima/trace/reference_renderer.h"
#include "envmap_test_util.h"
#include "reflect_test_scenes.h"

namespace proxima {
namespace {

// The 12 × 4 × 8 m box room (reflect_test_scenes.h) with a few diffuse boxes and a mirror
// sphere of radius `radius` at each of `centers`.
Scene room_with_spheres(std::span<const vec3> centers, float radius) {
  Scene s = reflect_test::box_room({-6, 0, -4}, {6, 4, 4});
  const uint32_t grey = reflect_test::add_diffuse(s, vec3(0.7f));
  Mesh box = make_box(vec3(0.8f, 1.2f, 0.8f));
  for (vec3 at : {vec3(-4.5f, 0.6f, -2.5f), vec3(-2.5f, 0.6f, 0.5f), vec3(2.5f, 0.6f, -2.5f), vec3(4.5f, 0.6f, 0.5f)}) {
    Mesh m = box;
    for (vec3& p : m.positions) p += at;
    add_object(s, m, "box", grey);
  }
  Material mirror;
  mirror.name = "mirror";
  mirror.diffuse = vec3(0.0f);
  mirror.specular = 1.0f;
  const uint32_t mm = add_material(s, mirror);
  for (vec3 c : centers) {
    Mesh m = make_sphere(radius, 48, 24);
    for (vec3& p : m.positions) p += c;
    add_object(s, m, "sphere", mm);
  }
  return s;
}

using envmap_test::reflector_mae;

struct Grouped {
  size_t maps = 0;      // groups made
  double error = 0.0;  // rectified error against the one-bounce reference
};

// Rectified env mapping of the frame with the reflectors grouped by `options`.
Grouped grouped(const Scene& scene, const RayScene& rays, const Camera& cam, const EnvmapGroupOptions& options) {
  ReferenceOptions ro;
  ro.area_light_samples = 1;
  ro.max_bounces = 1;
  const ImageF reference = render_reference(scene, rays, cam, ro);
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  EnvmapSetOptions so;
  so.grouping = options;
  so.map.resolution = 128;
  so.map.area_light_samples = 1;
  const EnvmapSet set = build_envmap_set(scene, rays, reflectors, so);
  EnvmapInputs in;
  in.method = EnvmapMethod::Rectified;
  in.area_light_samples = 1;
  in.rectify.D = scene_bounds(scene).diagonal();
  in = with_envmap_set(in, set);
  const ReflectorPixels pixels = rasterize_reflector_pixels(scene, cam, reflectors);
  EXPECT_GT(pixels.count, 1000u);
  return {set.groups.size(), reflector_mae(shade_reflector_pixels(scene, rays, cam, pixels, in).color, reference, pixels)};
}

TEST(EnvmapGroups, ReflectorsFarApartGetTheirOwnMapsAndASmallerRectifiedError) {
  const vec3 centers[] = {{-4.0f, 1.0f, -1.0f}, {4.0f, 1.0f, -1.0f}};
  const Scene scene = room_with_spheres(centers, 0.6f);
  const RayScene rays(scene);
  const Camera cam = look_at({0.0f, 2.0f, 3.8f}, {0.0f, 1.0f, -1.0f}, {0, 1, 0}, 90.0f, 320, 240);
  const Grouped own = grouped(scene, rays, cam, {}), shared = grouped(scene, rays, cam, {.max_groups = 1});
  EXPECT_EQ(own.maps, 2u);
  EXPECT_EQ(shared.maps, 1u);
  EXPECT_LT(own.error, shared.error / 3.0) << "per-reflector " << own.error << " vs shared " << shared.error;
}

// The reflection frame's lookups (the cluster study's comparison, the viewer) read each
// sample's own group too: against Embree on the same rays, a map per sphere errs far less
// than one shared map.
TEST(EnvmapGroups, FrameReflectionsReadEachSamplesGroup) {
  const vec3 centers[] = {{-4.0f, 1.0f, -1.0f}, {4.0f, 1.0f, -1.0f}};
  const Scene scene = room_with_spheres(centers, 0.6f);
  const RayScene rays(scene);
  const Camera cam = look_at({0.0f, 2.0f, 3.8f}, {0.0f, 1.0f, -1.0f}, {0, 1, 0}, 90.0f, 320, 240);
  ReflectionOptions ro;
  ro.supersample = 1;
  ro.area_light_samples = 1;
  const ReflectionFrame frame = prepare_reflection_frame(scene, cam, ro);
  ASSERT_GT(frame.sample_count(), 1000u);
  const TracedReflections traced = trace_reflections(scene, rays, frame);
  auto error = [&](const EnvmapGroupOptions& grouping, size_t maps) {
    EnvmapSetOptions so;
    so.grouping = grouping;
    so.map.resolution = 128;
    so.map.area_light_samples = 1;
    so.map.shade = [&](uint32_t t, float u, float v, vec3 toward) {
      return shade_reflected_point(scene, t, u, v, toward, 1);
    };
    const EnvmapSet set = build_envmap_set(scene, rays, reflective_objects(scene), so);
    EXPECT_EQ(set.groups.size(), maps);
    EnvmapInputs in;
    in.method = EnvmapMethod::Rectified;
    in.rectify.D = scene_bounds(scene).diagonal();
    const std::vector<vec3> r = envmap_frame_reflections(scene, frame, with_envmap_set(in, set));
    double sum = 0.0;
    for (size_t i = 0; i < r.size(); ++i) {
      const vec3 d = glm::abs(r[i] - traced.radiance[i]);
      sum += double(d.x + d.y + d.z) / 3.0;
    }
    return sum / double(r.size());
  };
  const double own = error({}, 2), shared = error({.max_groups = 1}, 1);
  EXPECT_LT(own, shared / 3.0) << "per-reflector " << own << " vs shared " << shared;
}

TEST(EnvmapGroups, ReflectorsCloseTogetherShareAMap) {
  const vec3 centers[] = {{-0.3f, 2.0f, 0.0f}, {0.3f, 2.0f, 0.0f}, {4.0f, 1.0f, 0.0f}};
  const Scene scene = room_with_spheres(centers, 0.2f);
  const RayScene rays(scene);
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  ASSERT_EQ(reflectors.size(), 3u);
  const std::vector<EnvmapGroup> groups = group_reflectors(scene, rays, reflectors, {});
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].reflectors, (std::vector<uint32_t>{reflectors[0], reflectors[1]}));
  EXPECT_LE(groups[0].parallax, EnvmapGroupOptions{}.max_parallax);
  EXPECT_NEAR(groups[0].center.x, 0.0f, 1e-4f);
  EXPECT_NEAR(groups[0].radius, 0.5f, 0.01f);
  EXPECT_EQ(groups[1].reflectors, (std::vector<uint32_t>{reflectors[2]}));
  const std::vector<uint32_t> group_of = envmap_group_of_objects(scene, groups);
  EXPECT_EQ(group_of[reflectors[1]], 0u);
  EXPECT_EQ(group_of[reflectors[2]], 1u);
  EXPECT_EQ(group_of[0], kNoEnvmapGroup);  // a wall
  // The shared map costs the close pair little: its rectified error stays near that of a map each.
  const Camera cam = look_at({0.0f, 2.2f, 1.5f}, {0.0f, 2.0f, 0.0f}, {0, 1, 0}, 45.0f, 320, 240);
  const Grouped shared = grouped(scene, rays, cam, {}), own = grouped(scene, rays, cam, {.max_parallax = 0.0f});
  EXPECT_EQ(shared.maps, 2u);
  EXPECT_EQ(own.maps, 3u);
  EXPECT_LT(shared.error, 1.5 * own.error) << "shared " << shared.error << " vs a map each " << own.error;
}

TEST(EnvmapGroups, TheNumberOfMapsIsBoundedAndTheGroupingDeterministic) {
  std::vector<vec3> centers;
  for (int i = 0; i < 8; ++i) centers.push_back({-5.0f + 10.0f * float(i) / 7.0f, 1.0f + 0.2f * float(i % 3), -1.0f});
  const Scene scene = room_with_spheres(centers, 0.3f);
  const RayScene rays(scene);
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  std::vector<EnvmapGroup> one, two;
  {
    ThreadLimit limit(1);
    one = group_reflectors(scene, rays, reflectors, {.max_groups = 3});
  }
  {
    ThreadLimit limit(2);
    two = group_reflectors(scene, rays, reflectors, {.max_groups = 3});
  }
  ASSERT_EQ(one.size(), 3u);
  size_t covered = 0;
  for (size_t g = 0; g < one.size(); ++g) {
    EXPECT_EQ(one[g].reflectors, two[g].reflectors);
    EXPECT_EQ(one[g].parallax, two[g].parallax);
    covered += one[g].reflectors.size();
  }
  EXPECT_EQ(covered, reflectors.size());
  EXPECT_EQ(group_reflectors(scene, rays, reflectors, {.max_groups = 1}).size(), 1u);
}

TEST(EnvmapGroups, ASingleReflectorKeepsTheProjectionCenter) {
  const vec3 centers[] = {{1.0f, 1.5f, -0.5f}};
  const Scene scene = room_with_spheres(centers, 0.5f);
  const RayScene rays(scene);
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  const std::vector<EnvmapGroup> groups = group_reflectors(scene, rays, reflectors, {});
  ASSERT_EQ(groups.size(), 1u);
  const vec3 c = projection_center(scene, reflectors);
  EXPECT_EQ(groups[0].center.x, c.x);
  EXPECT_EQ(groups[0].center.y, c.y);
  EXPECT_EQ(groups[0].center.z, c.z);
  EXPECT_EQ(groups[0].radius, viewer_radius(scene, reflectors, c));
  EXPECT_GT(groups[0].parallax, 0.0f);
  EXPECT_LT(groups[0].parallax, 0.5f);
}

TEST(EnvmapGroups, BadOptionsAreInputErrors) {
  const vec3 centers[] = {{0.0f, 1.0f, 0.0f}};
  const Scene scene = room_with_spheres(centers, 0.5f);
  const RayScene rays(scene);
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  EXPECT_THROW(group_reflectors(scene, rays, reflectors, {.max_groups = 0}), InputError);
  EXPECT_THROW(group_reflectors(scene, rays, reflectors, {.max_groups = kMaxEnvmapGroups + 1}), InputError);
  EXPECT_THROW(group_reflectors(scene, rays, reflectors, {.max_parallax = -1.0f}), InputError);
  EXPECT_THROW(group_reflectors(scene, rays, reflectors, {.max_parallax = std::nanf("")}), InputError);
}

}  // namespace
}  // namespace proxima
