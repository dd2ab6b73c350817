// Real-geometry failure classes of exact visibility, built by hand the way brush-based level
// editors build levels: a T-junction crack, coplanar overlapping faces of different brushes,
// unwelded seams (vertices 1e-5..1e-4 m apart: slight gaps and slight overlaps), an eye next
// to a sliver, open meshes, interpenetrating boxes, centimetre details in a 100 m level and a
// small brush level with all of them at once. Each viewpoint must hold the per-view targets
// against Embree: agreement ≥ 99.9 %, interior agreement ≥ 99.99 % (a different polygon
// through the ray's hit point, within the snap tolerance, is a tie and agrees), no occluded label, no
// unplaced fragment, and every beam bounded: in a closed level no beam leaves the outer box,
// and the beams traced stay proportional to the regions they end in.
#include <gtest/gtest.h>

#include <string>

#include "proxima/core/rng.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/oracle.h"
#include "proxima/visibility/visibility_map.h"
#include "visibility/hand_built_scene.h"

namespace proxima::visibility {
namespace {

constexpr int kW = 160, kH = 120;

Scene empty_scene() {
  Scene s;
  add_material(s, Material{});
  return s;
}

struct Case {
  Scene scene;
  std::vector<Camera> cameras;
  bool closed = true;  // every sightline hits geometry (Embree agrees: checked)
};

// Builds the winged pair and checks every viewpoint against Embree and the targets.
void expect_exact(const Case& c, const std::string& what) {
  SCOPED_TRACE(what);
  const ModelPolygons model = extract_polygons(c.scene);
  BspStats stats;
  const WingedPair wp = build_winged_pair(model, {}, &stats);
  ASSERT_EQ(wp.loop_offset.size(), wp.faces.size() + 1) << "finalize failed";
  EXPECT_EQ(stats.unplaced_fragments, 0u);
  const RayScene rays(c.scene);
  for (const Camera& cam : c.cameras) {
    SCOPED_TRACE("eye " + std::to_string(cam.position.x) + ", " + std::to_string(cam.position.y) + ", " +
                 std::to_string(cam.position.z));
    const VisibilityMap map = trace_visibility_map(wp, cam);
    const OracleCounts o = compare_with_ray_casts(map, model, c.scene, rays, cam);
    EXPECT_GE(o.agreement_with_ties_pct(), 99.9);
    EXPECT_GE(o.interior_with_ties_pct(), 99.99);
    EXPECT_EQ(o.occluded_label, 0u);
    // Beams stay bounded: none escapes a closed level, and the count is proportional to
    // the final regions (each region's chain of transparent cells is short).
    if (c.closed) {
      size_t escaped = 0;
      for (const MapRegion& r : map.regions) escaped += r.polygon == kNone;
      EXPECT_EQ(escaped, 0u);
    }
    EXPECT_LE(map.stats.beams, 32 * map.stats.regions + 64) << "regions " << map.stats.regions;
  }
}

std::vector<Camera> around(vec3 eye, vec3 target, float fov = 80.0f) {
  return {look_at(eye, target, {0, 1, 0}, fov, kW, kH, 1e-5f, 1e4f)};
}

// A closed 20 m room (inward walls) for the small cases to sit in.
Case in_room() {
  Case c{empty_scene(), {}, true};
  add_box(c.scene, {-10, -3, -10}, {10, 7, 10}, -1, true);
  return c;
}

// A big slab top abutting two smaller coplanar slab tops: the big face's edge has no vertex
// where the two small faces meet (a T-junction). Seen at grazing angles along the seam,
// a crack between the faces would show the floor far below.
TEST(VisibilityRealGeometry, TJunctionCrack) {
  Case c = in_room();
  add_box(c.scene, {-4, -1, -4}, {0, 0, 4});
  add_box(c.scene, {0, -1, -4}, {4, 0, 0});
  add_box(c.scene, {0, -1, 0}, {4, 0, 4});
  add_box(c.scene, {-1, 0, -1}, {1, 0.5f, 1e-3f});  // a step on the seam (another T-junction)
  c.cameras = around({0.01f, 0.3f, 3.5f}, {0.0f, 0.0f, -4.0f}, 70.0f);
  for (const Camera& k : around({-0.2f, 0.05f, 3.9f}, {0.05f, 0.0f, -4.0f}, 60.0f)) c.cameras.push_back(k);
  for (const Camera& k : around({5.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 60.0f)) c.cameras.push_back(k);
  expect_exact(c, "T-junction");
}

// Brushes overlapping without CSG: top faces coplanar and overlapping, side faces coplanar
// and overlapping, a face of one brush inside the other.
TEST(VisibilityRealGeometry, CoplanarOverlappingBrushes) {
  Case c = in_room();
  add_box(c.scene, {-3, -3, -3}, {1, 0, 1});
  add_box(c.scene, {-1, -3, -1}, {3, 0, 3});    // same top plane, overlapping
  add_box(c.scene, {-1, -3, -3}, {3, 1, -2});   // same −z plane as the first
  add_box(c.scene, {-3, -3, -3}, {1, 0, 1});    // an exact duplicate brush
  c.cameras = around({0.3f, 2.0f, 5.0f}, {0.0f, -1.0f, 0.0f});
  for (const Camera& k : around({4.0f, 0.5f, -6.0f}, {0.0f, -1.0f, -2.0f})) c.cameras.push_back(k);
  for (const Camera& k : around({-0.5f, 0.2f, 0.5f}, {2.0f, 0.0f, 2.0f}, 90.0f)) c.cameras.push_back(k);
  expect_exact(c, "coplanar overlapping brushes");
}

// Faces meeting with vertices 1e-5..1e-4 m apart: a wall of two brushes with a slight gap,
// another with a slight overlap, a floor tile raised by 3e-5, a corner that misses by 5e-5.
TEST(VisibilityRealGeometry, UnweldedSeams) {
  Case c = in_room();
  add_box(c.scene, {-6, -3, -2}, {0, 2, -1.5f});
  add_box(c.scene, {1e-4f, -3, -2}, {6, 2, -1.5f});               // gap 1e-4
  add_box(c.scene, {-6, -3, 2}, {0.00005f, 2, 2.5f});
  add_box(c.scene, {-1e-5f, -3, 2}, {6, 2, 2.5f});                 // overlap 6e-5
  add_box(c.scene, {-2, -3, -1.5f}, {2, -2, 2});
  add_box(c.scene, {-1, -3, -0.5f}, {1, -2 + 3e-5f, 0.5f});        // raised 3e-5
  add_box(c.scene, {3, -3, -1.5f + 5e-5f}, {3.5f, 2, 2 - 2e-5f});  // corner gaps
  c.cameras = around({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -2.0f});
  for (const Camera& k : around({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 2.0f})) c.cameras.push_back(k);
  for (const Camera& k : around({-4.0f, 1.5f, 0.0f}, {4.0f, -2.0f, 0.0f})) c.cameras.push_back(k);
  for (const Camera& k : around({0.5f, -1.0f, -1.4f}, {0.0f, -1.0f, -2.0f}, 100.0f)) c.cameras.push_back(k);
  expect_exact(c, "unwelded seams");
}

// An eye 1 mm from a sliver (a 0.1 mm-thick triangle fan and a 1 mm plank) looking along it.
TEST(VisibilityRealGeometry, EyeNextToASliver) {
  Case c = in_room();
  add_mesh(c.scene, {{-3, 0, -3}, {3, 0, -3}, {0, 1e-4f, 3}}, {{0, 2, 1}, {0, 1, 2}});
  add_box(c.scene, {-2, 1, -3}, {2, 1.001f, 3});
  add_box(c.scene, {-0.5f, -3, -0.5f}, {0.5f, 0, 0.5f});
  c.cameras = around({0.0f, 1e-3f + 1e-4f, 2.0f}, {0.0f, 0.0f, -3.0f}, 90.0f);
  for (const Camera& k : around({0.2f, 1.0025f, 0.0f}, {1.0f, 1.0f, -3.0f}, 90.0f)) c.cameras.push_back(k);
  for (const Camera& k : around({0.2f, 0.9995f, 0.0f}, {-1.0f, 1.0f, 3.0f}, 90.0f)) c.cameras.push_back(k);
  expect_exact(c, "eye next to a sliver");
}

// Open meshes with nothing behind them: single-sided quads seen from both sides, a box
// without its top, looked into and at from outside.
TEST(VisibilityRealGeometry, OpenMeshes) {
  Case c{empty_scene(), {}, false};
  add_quad(c.scene, {-3, -1, -3}, {2, 0, 0}, {0, 2, 0}, {0, 0, 5});
  add_quad(c.scene, {1, -1, -3}, {0, 0, 2}, {0, 2, 0}, {5, 0, 0});
  add_box(c.scene, {-1, -2, 0}, {1, -0.5f, 2}, 3);
  add_box(c.scene, {2, -2, 0}, {3, 0, 1}, 0);
  c.cameras = around({0.0f, 1.5f, 4.0f}, {0.0f, -1.5f, 1.0f});
  for (const Camera& k : around({0.0f, 0.5f, -5.0f}, {0.0f, 0.0f, 0.0f})) c.cameras.push_back(k);
  for (const Camera& k : around({0.0f, -1.0f, 1.0f}, {2.0f, -1.0f, 1.0f}, 90.0f)) c.cameras.push_back(k);
  expect_exact(c, "open meshes");
}

// Boxes crossing each other (no coplanar faces) and a slanted brush through them.
TEST(VisibilityRealGeometry, InterpenetratingBoxes) {
  Case c = in_room();
  add_box(c.scene, {-3, -2, -2}, {2, 1, 1});
  add_box(c.scene, {-1.3f, -2.7f, -2.9f}, {0.7f, 2.3f, 0.3f});
  add_box(c.scene, {-2.2f, -0.4f, -0.8f}, {3.1f, 0.6f, 2.2f});
  add_mesh(c.scene, {{-4, -3, 1.5f}, {4, -3, -1.0f}, {4, 2, -1.7f}, {-4, 2, 0.8f}}, {{0, 1, 2}, {0, 2, 3}});
  c.cameras = around({1.0f, 1.5f, 6.0f}, {0.0f, 0.0f, 0.0f});
  for (const Camera& k : around({-6.0f, 3.0f, -5.0f}, {0.0f, 0.0f, 0.0f})) c.cameras.push_back(k);
  expect_exact(c, "interpenetrating boxes");
}

// A 100 m level with centimetre details (a 1 cm grille of 2 mm bars, 1 cm cubes) near the eye.
TEST(VisibilityRealGeometry, MixedScales) {
  Case c{empty_scene(), {}, true};
  add_box(c.scene, {-50, -5, -50}, {50, 20, 50}, -1, true);
  add_box(c.scene, {-30, -5, -30}, {-20, 10, 30});
  for (int i = 0; i < 8; ++i) add_box(c.scene, {-0.04f + 0.01f * i, -0.05f, -0.3f}, {-0.038f + 0.01f * i, 0.05f, -0.29f});
  for (int i = 0; i < 6; ++i) add_box(c.scene, {0.1f + 0.02f * i, -0.01f, -0.2f}, {0.11f + 0.02f * i, 0.0f, -0.19f});
  c.cameras = around({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 40.0f);
  for (const Camera& k : around({0.0f, 0.02f, 0.0f}, {0.15f, -0.01f, -0.2f}, 60.0f)) c.cameras.push_back(k);
  for (const Camera& k : around({10.0f, 1.0f, 10.0f}, {-25.0f, 0.0f, 0.0f})) c.cameras.push_back(k);
  expect_exact(c, "mixed scales");
}

// A small brush level: random axis-aligned brushes on a 0.25 m grid (coplanar overlaps,
// T-junctions, boxes inside boxes) plus unwelded jitter of up to 1e-4 m on some brushes,
// in a closed hall; eyes at random free points.
TEST(VisibilityRealGeometry, RandomBrushLevel) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    Case c{empty_scene(), {}, true};
    Pcg32 rng(seed);
    add_box(c.scene, {-20, -1, -20}, {20, 9, 20}, -1, true);
    std::vector<std::pair<vec3, vec3>> boxes;
    for (int i = 0; i < 80; ++i) {
      auto grid = [&](float lo, float hi) { return std::round((lo + (hi - lo) * rng.next_float()) * 4.0f) / 4.0f; };
      vec3 lo(grid(-19, 17), grid(-1, 6), grid(-19, 17));
      vec3 size(grid(0.25f, 6), grid(0.25f, 4), grid(0.25f, 6));
      vec3 hi = lo + size;
      if (rng.next_float() < 0.3f) {
        const float j = 1e-4f * (rng.next_float() - 0.5f) * 2.0f;
        lo += vec3(j, 0.0f, -j);
        hi += vec3(0.0f, j, j);
      }
      add_box(c.scene, lo, hi);
      boxes.push_back({lo, hi});
    }
    for (int k = 0; k < 4; ++k) {
      vec3 eye;
      for (bool inside = true; inside;) {
        eye = {-18 + 36 * rng.next_float(), -0.5f + 9 * rng.next_float(), -18 + 36 * rng.next_float()};
        inside = false;
        for (const auto& [lo, hi] : boxes)
          inside |= glm::all(glm::greaterThan(eye, lo - 0.05f)) && glm::all(glm::lessThan(eye, hi + 0.05f));
      }
      const vec3 target = eye + vec3(rng.next_float() - 0.5f, 0.3f * (rng.next_float() - 0.5f), rng.next_float() - 0.5f);
      for (const Camera& cam : around(eye, target, 90.0f)) c.cameras.push_back(cam);
    }
    expect_exact(c, "random brush level seed " + std::to_string(seed));
  }
}

}  // namespace
}  // namespace proxima::visibility
