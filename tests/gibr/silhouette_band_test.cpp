// The band of a novel view near the photographs' silhouettes (gibr/silhouette_band.h), on a
// constructed case: a box in front of a wall, photographed head-on, seen from 0.5 m to the
// side. The photograph's silhouette (the box's front outline) lifted onto the wall is the
// box's outline scaled by the depth ratio; the novel view sees its right side and not its
// left, which the box hides.
#include "proxima/gibr/silhouette_band.h"

#include <gtest/gtest.h>

#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/polygons.h"
#include "proxima/visibility/winged_pair.h"
#include "visibility/hand_built_scene.h"

namespace proxima::gibr {
namespace {

using namespace proxima::visibility;

TEST(GibrSilhouetteBand, PhotographsSilhouettesReprojectWhereTheViewSeesThem) {
  Scene s;
  add_material(s, Material{});
  add_quad(s, {-6, -4, -6}, {12, 0, 0}, {0, 8, 0}, {0, 0, 0});  // the wall, facing the eye
  add_box(s, {-0.25f, -1, -3.25f}, {0.25f, 1, -2.75f});          // the occluder
  const ModelPolygons model = extract_polygons(s);
  const WingedPair wp = build_winged_pair(model);
  const RayScene rays(s);
  const Camera photo = look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60.0f, 160, 120, 0.01f, 100.0f);
  const std::vector<LiftedEdge> edges = lift_silhouettes(trace_visibility_map(wp, photo), photo, model, 0);
  // Every lifted point lies on the wall (z = −6) or on the box's front face (z = −2.75), on
  // the scaled outline: |x| = 0.25 · depth / 2.75 or |y| = 1 · depth / 2.75.
  ASSERT_FALSE(edges.empty());
  size_t on_wall = 0;
  for (const LiftedEdge& e : edges)
    for (const dvec3& p : {e.a, e.b}) {
      const double depth = -p.z;
      ASSERT_TRUE(std::abs(depth - 6.0) < 1e-6 || std::abs(depth - 2.75) < 1e-6) << p.z;
      on_wall += std::abs(depth - 6.0) < 1e-6;
      const double sx = std::abs(p.x) * 2.75 / depth, sy = std::abs(p.y) * 2.75 / depth;
      EXPECT_TRUE((std::abs(sx - 0.25) < 1e-6 && sy <= 1.0 + 1e-6) || (std::abs(sy - 1.0) < 1e-6 && sx <= 0.25 + 1e-6))
          << p.x << " " << p.y << " " << p.z;
    }
  EXPECT_GT(on_wall, 0u);

  const Camera view = look_at({0.5f, 0, 0}, {0.5f, 0, -1}, {0, 1, 0}, 60.0f, 160, 120, 0.01f, 100.0f);
  const ImageU8 band = reprojected_edge_mask(edges, view, rays, 2.0, model.scale);
  auto pixel_of = [&](vec3 p) {
    const auto q = project(view, p);
    return ivec2(int(std::floor(q->pixel.x)), int(std::floor(q->pixel.y)));
  };
  // The right edge of the box's shadow on the wall: seen, in the band — 10 px from the
  // view's own silhouettes (the box's right side at x = 0.25 projects 10 px to its left).
  const ivec2 right = pixel_of({0.25f * 6.0f / 2.75f, 0.0f, -6.0f});
  EXPECT_EQ(band.at(right.x, right.y), 1);
  EXPECT_GE(pixel_of({0.25f, 0.0f, -2.75f}).x, right.x - 11);
  EXPECT_LE(pixel_of({0.25f, 0.0f, -2.75f}).x, right.x - 8);
  // The left edge of the shadow: hidden behind the box in this view, not in the band.
  const ivec2 left = pixel_of({-0.25f * 6.0f / 2.75f, 0.0f, -6.0f});
  EXPECT_EQ(band.at(left.x, left.y), 0);
  // The box's front outline (lifted onto the box) is seen: its left edge is in the band.
  const ivec2 box_left = pixel_of({-0.25f, 0.0f, -2.75f});
  EXPECT_EQ(band.at(box_left.x, box_left.y), 1);
  // Far from every lifted edge: not in the band; the band is about 4 px wide per line.
  EXPECT_EQ(band.at(right.x + 20, right.y), 0);
  int row = 0;
  for (int x = 0; x < band.width(); ++x) row += band.at(x, 60);
  EXPECT_GE(row, 3 * 4);
  EXPECT_LE(row, 3 * 5 + 2);
}

}  // namespace
}  // namespace proxima::gibr
