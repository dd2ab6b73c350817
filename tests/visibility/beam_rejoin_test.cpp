// Output-sensitive beam tracing on geometry whose free space the BSP cuts into many cells:
// a hall cluttered with crates of all sizes (every crate face's plane cuts the space around
// it) and a building open to the outside through a window. Rejoining beam pieces and ending
// escaping beams must never change a label at any pixel center, and must cut the beams
// traced; the oracle's snap ties and the welded geometry are checked on known answers.
#include <gtest/gtest.h>

#include <string>

#include "proxima/core/rng.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/oracle.h"
#include "proxima/visibility/visibility_map.h"
#include "visibility/hand_built_scene.h"

namespace proxima::visibility {
namespace {

constexpr int kW = 160, kH = 120;

Scene cluttered_hall(uint64_t seed, std::vector<vec3>& eyes) {
  Scene s;
  add_material(s, Material{});
  add_box(s, {-15, 0, -15}, {15, 8, 15}, -1, true);
  Pcg32 rng(seed);
  std::vector<std::pair<vec3, vec3>> boxes;
  for (int i = 0; i < 120; ++i) {
    const vec3 lo(-14 + 27 * rng.next_float(), 3 * rng.next_float(), -14 + 27 * rng.next_float());
    const vec3 hi = lo + vec3(0.2f + 1.5f * rng.next_float(), 0.2f + 2.5f * rng.next_float(), 0.2f + 1.5f * rng.next_float());
    add_box(s, lo, hi);
    boxes.push_back({lo, hi});
  }
  while (eyes.size() < 4) {
    const vec3 e(-13 + 26 * rng.next_float(), 0.5f + 6 * rng.next_float(), -13 + 26 * rng.next_float());
    bool inside = false;
    for (const auto& [lo, hi] : boxes)
      inside |= glm::all(glm::greaterThan(e, lo - 0.1f)) && glm::all(glm::lessThan(e, hi + 0.1f));
    if (!inside) eyes.push_back(e);
  }
  return s;
}

// Pixels whose label differs between two maps of one camera.
size_t differing_labels(const VisibilityMap& a, const VisibilityMap& b) {
  const ImageU32 la = rasterize_map(a), lb = rasterize_map(b);
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) n += la.at(x, y) != lb.at(x, y);
  return n;
}

// Beams split by every transparent face they cross and never rejoined multiply with the
// cells a sightline passes; rejoined, they follow what is visible. Same labels either way.
TEST(BeamRejoin, CutsTheBeamsOfAClutteredHallAndKeepsEveryLabel) {
  for (uint64_t seed : {1u, 2u}) {
    std::vector<vec3> eyes;
    const Scene scene = cluttered_hall(seed, eyes);
    const ModelPolygons model = extract_polygons(scene);
    const WingedPair wp = build_winged_pair(model);
    const RayScene rays(scene);
    size_t beams_on = 0, beams_off = 0;
    for (const vec3& eye : eyes) {
      SCOPED_TRACE(testing::Message() << "seed " << seed << " eye " << eye.x << ", " << eye.z);
      const Camera cam = look_at(eye, eye + vec3(1.0f, -0.2f, 0.7f), {0, 1, 0}, 90.0f, kW, kH, 1e-4f, 1e4f);
      const VisibilityMap on = trace_visibility_map(wp, cam);
      const VisibilityMap off = trace_visibility_map(wp, cam, {.rejoin = false});
      EXPECT_EQ(differing_labels(on, off), 0u);
      const OracleCounts c = compare_with_ray_casts(on, model, scene, rays, cam);
      EXPECT_GE(c.agreement_with_ties_pct(), 99.9);
      EXPECT_GE(c.interior_with_ties_pct(), 99.99);
      EXPECT_EQ(c.occluded_label, 0u);
      EXPECT_LE(on.stats.regions, off.stats.regions);
      beams_on += on.stats.beams;
      beams_off += off.stats.beams;
    }
    std::printf("[ rejoin ] seed %d: beams %zu rejoined, %zu not\n", int(seed), beams_on, beams_off);
    EXPECT_LE(3 * beams_on, beams_off);
  }
}

// A closed room with a window (a wall of four boxes around an opening) and crates outside:
// the sightlines through the window meet the crates or leave for the background. Beams that
// have left the geometry's bounds end there; the labels are the same as when they are
// traced on to the outer box.
TEST(BeamRejoin, EscapingBeamsEndAsBackgroundWithTheSameLabels) {
  Scene s;
  add_material(s, Material{});
  add_box(s, {-5, 0, -5}, {5, 0.2f, 5});        // floor
  add_box(s, {-5, 3, -5}, {5, 3.2f, 5});        // ceiling
  add_box(s, {-5, 0.2f, 4.8f}, {5, 3, 5});      // back wall
  add_box(s, {-5, 0.2f, -5}, {-4.8f, 3, 5});    // side walls
  add_box(s, {4.8f, 0.2f, -5}, {5, 3, 5});
  add_box(s, {-4.8f, 0.2f, -5}, {-1, 3, -4.8f});  // front wall around a 2 × 1.3 m window
  add_box(s, {1, 0.2f, -5}, {4.8f, 3, -4.8f});
  add_box(s, {-1, 0.2f, -5}, {1, 1, -4.8f});
  add_box(s, {-1, 2.3f, -5}, {1, 3, -4.8f});
  for (int i = 0; i < 6; ++i) add_box(s, {-6.0f + 2.2f * i, 0, -9.0f - 0.7f * i}, {-5.2f + 2.2f * i, 1.5f + 0.3f * i, -8.0f - 0.7f * i});
  const ModelPolygons model = extract_polygons(s);
  const WingedPair wp = build_winged_pair(model);
  const RayScene rays(s);
  size_t escaped = 0;
  for (const vec3 eye : {vec3(0, 1.6f, 2), vec3(-2, 1.2f, 0), vec3(0.3f, 1.7f, -4.0f)}) {
    SCOPED_TRACE(testing::Message() << "eye " << eye.x << ", " << eye.z);
    const Camera cam = look_at(eye, {0, 1.3f, -8}, {0, 1, 0}, 80.0f, kW, kH, 1e-4f, 1e4f);
    const VisibilityMap on = trace_visibility_map(wp, cam);
    const VisibilityMap off = trace_visibility_map(wp, cam, {.escape = false});
    EXPECT_EQ(differing_labels(on, off), 0u);
    const OracleCounts c = compare_with_ray_casts(on, model, s, rays, cam);
    EXPECT_GE(c.agreement_with_ties_pct(), 99.9);
    EXPECT_EQ(c.occluded_label, 0u);
    EXPECT_LE(on.stats.beams, off.stats.beams);
    EXPECT_EQ(off.stats.escaped, 0u);
    escaped += on.stats.escaped;
  }
  EXPECT_GT(escaped, 0u);  // the test exercises the escape
}

// A ray within the snap tolerance of a polygon's edge grazes it (an edge welding or plane
// snapping may have moved by that much); one farther out, or through the middle, does not.
TEST(OracleTies, RayGrazingAnEdgeWithinTheSnapTolerance) {
  Scene s;
  add_material(s, Material{});
  add_quad(s, {-1, -1, -5}, {2, 0, 0}, {0, 2, 0}, {0, 0, 0});
  add_quad(s, {-100, -100, -50}, {200, 0, 0}, {0, 200, 0}, {0, 0, 0});  // sets the scale
  const ModelPolygons model = extract_polygons(s);
  const double snap = kSnapTolerance * model.scale;
  const uint32_t quad = model.triangle_polygon[0];
  auto through = [&](double x) { return glm::normalize(dvec3(x, 0.0, -5.0)); };
  EXPECT_TRUE(ray_grazes_outline(model, quad, dvec3(0.0), through(1.0 + 0.5 * snap)));
  EXPECT_TRUE(ray_grazes_outline(model, quad, dvec3(0.0), through(1.0 - 0.5 * snap)));
  EXPECT_FALSE(ray_grazes_outline(model, quad, dvec3(0.0), through(1.0 + 3.0 * snap)));
  EXPECT_FALSE(ray_grazes_outline(model, quad, dvec3(0.0), through(0.0)));
}

// The welded scene: vertices within the snap tolerance of an earlier one take its position
// (an input position), the others keep theirs; triangles and objects are unchanged.
TEST(OracleTies, WeldedSceneMovesVerticesWithinTheSnapTolerance) {
  Scene s;
  add_material(s, Material{});
  add_box(s, {0, 0, 0}, {1, 1, 1});
  add_box(s, {1.00005f, 0, 0}, {2, 1, 1});  // an unwelded seam, 5e-5 m apart
  add_box(s, {0, 2, 0}, {10, 3, 10});
  const ModelPolygons model = extract_polygons(s);
  const Scene w = welded_scene(s, model);
  const double snap = kSnapTolerance * model.scale;
  ASSERT_EQ(w.positions.size(), s.positions.size());
  EXPECT_EQ(w.triangles, s.triangles);
  size_t moved = 0;
  for (size_t i = 0; i < s.positions.size(); ++i) {
    EXPECT_LE(glm::length(dvec3(w.positions[i]) - dvec3(s.positions[i])), snap);
    moved += w.positions[i] != s.positions[i];
  }
  EXPECT_EQ(moved, 4u);  // the second box's four corners at x = 1.00005 join the first's
  EXPECT_EQ(w.positions[8], s.positions[1]);  // (1.00005, 0, 0) → (1, 0, 0)
}

}  // namespace
}  // namespace proxima::visibility
