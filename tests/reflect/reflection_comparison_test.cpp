// The pixels a reflection method is judged on and the objects the reference's mirror rays
// meet there: on room-reflector (a closed room, so every mirror ray meets a wall) and on
// hand-made masks for the set operations.
#include "proxima/reflect/reflection_comparison.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "proxima/core/parallel.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_select.h"

namespace proxima {
namespace {

struct RoomReflector {
  Scene scene = make_builtin_scene("room-reflector");
  RayScene rays{scene};
  std::vector<uint32_t> reflectors = reflective_objects(scene);
  Camera camera = pick_camera(scene, {}, 64, 48);
  ItemBuffer item = trace_item_buffer(scene, rays, camera);
  ReflectorPixels pixels = rasterize_reflector_pixels(scene, camera, reflectors);
};

bool is_reflector(const RoomReflector& r, uint32_t triangle) {
  return triangle != kNoTriangle && std::find(r.reflectors.begin(), r.reflectors.end(),
                                              r.scene.triangle_object[triangle]) != r.reflectors.end();
}

TEST(ReflectionComparison, MaskIsWhereBothTheMethodAndTheReferenceSeeAReflector) {
  const RoomReflector r;
  const PixelMask m = comparison_mask(r.pixels.triangle, r.item, r.scene, r.reflectors);
  size_t both = 0, set = 0;
  for (size_t i = 0; i < m.mask.data().size(); ++i) {
    const bool expected = r.pixels.triangle.data()[i] != kNoTriangle && is_reflector(r, r.item.triangle.data()[i]);
    EXPECT_EQ(m.mask.data()[i], expected ? 1 : 0) << i;
    both += expected;
    set += m.mask.data()[i];
  }
  EXPECT_GT(both, 50u);
  EXPECT_EQ(m.pixels, set);
  // The rasterizer and Embree agree on all but a few silhouette pixels.
  EXPECT_GE(double(m.pixels), 0.95 * double(r.pixels.count));
}

TEST(ReflectionComparison, ReferenceMirrorRaysInAClosedRoomAllMeetAnObject) {
  const RoomReflector r;
  const PixelMask m = comparison_mask(r.pixels.triangle, r.item, r.scene, r.reflectors);
  ImageU32 a, b;
  {
    ThreadLimit limit(1);
    a = reference_reflected_objects(r.scene, r.rays, r.camera, r.item, m.mask);
  }
  {
    ThreadLimit limit(2);
    b = reference_reflected_objects(r.scene, r.rays, r.camera, r.item, m.mask);
  }
  EXPECT_TRUE(a == b);
  for (size_t i = 0; i < a.data().size(); ++i) {
    if (!m.mask.data()[i]) {
      EXPECT_EQ(a.data()[i], kNoObject) << i;
      continue;
    }
    ASSERT_LT(a.data()[i], r.scene.objects.size()) << i;
    // A convex reflector cannot see itself.
    EXPECT_EQ(std::count(r.reflectors.begin(), r.reflectors.end(), a.data()[i]), 0) << i;
  }
  EXPECT_EQ(object_match_pct(a, a, m), 100.0);
  const ImageU32 none(a.width(), a.height(), 1, kNoObject);
  EXPECT_EQ(object_match_pct(none, a, m), 0.0);
  EXPECT_EQ(environment_mask(m, a, r.reflectors).pixels, m.pixels);
}

TEST(ReflectionComparison, EnvironmentMaskDropsSelfReflectionsAndMatchCountsMaskPixelsOnly) {
  PixelMask m{ImageU8(4, 1, 1, 0), 3};
  ImageU32 reference(4, 1, 1, 0), objects(4, 1, 1, 0);
  const uint8_t in_mask[] = {1, 1, 1, 0};
  const uint32_t reference_ids[] = {7, 2, kNoObject, 2};  // object 2 is the reflector
  const uint32_t object_ids[] = {7, 5, kNoObject, 2};     // the last pixel matches but is not in the mask
  for (int x = 0; x < 4; ++x) {
    m.mask.at(x, 0) = in_mask[x];
    reference.at(x, 0) = reference_ids[x];
    objects.at(x, 0) = object_ids[x];
  }
  const std::vector<uint32_t> reflectors{2};
  const PixelMask env = environment_mask(m, reference, reflectors);
  EXPECT_EQ(env.pixels, 2u);
  for (int x = 0; x < 4; ++x) EXPECT_EQ(env.mask.at(x, 0), x == 0 || x == 2 ? 1 : 0) << x;
  EXPECT_NEAR(object_match_pct(objects, reference, m), 200.0 / 3.0, 1e-12);
  EXPECT_EQ(object_match_pct(objects, reference, PixelMask{ImageU8(4, 1, 1, 0), 0}), 100.0);
}

}  // namespace
}  // namespace proxima
