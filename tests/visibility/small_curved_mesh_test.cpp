// A failure class of exact visibility found on real content: small tessellated curved
// meshes (a 4 cm UV sphere of 24 × 12 quads, as IFC conversions make of knobs and
// fittings), whose pole fans put many non-coplanar planes through nearly one point. The BSP
// classifies vertices within its plane tolerance as on a plane, so its faces are convex
// only up to that tolerance; a face projection passed on as a beam must not keep the
// resulting reflex vertices (each would clip a wedge out of the next cell's faces: a hole).
// Every view's regions must cover the image (the self-check's area test) and every
// fragment must be placed. docs/visibility.md, "Robustness rules".
#include <gtest/gtest.h>

#include <cmath>

#include "proxima/core/rng.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/visibility_map.h"
#include "visibility/hand_built_scene.h"

namespace proxima::visibility {
namespace {

void add_uv_sphere(Scene& s, vec3 c, float radius, int nu, int nv) {
  std::vector<vec3> p;
  std::vector<uvec3> t;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const float th = 3.14159265f * float(j) / float(nv), ph = 6.2831853f * float(i) / float(nu);
      p.push_back(c + radius * vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)));
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const uint32_t a = uint32_t(j * nu + i), b = uint32_t(j * nu + (i + 1) % nu);
      const uint32_t c2 = uint32_t((j + 1) * nu + i), d = uint32_t((j + 1) * nu + (i + 1) % nu);
      if (j > 0) t.push_back({a, c2, b});
      if (j + 1 < nv) t.push_back({b, c2, d});
    }
  add_mesh(s, p, t);
}

TEST(VisibilitySmallCurvedMesh, MapsOfARoomWithASmallSphereHaveNoHoles) {
  Scene s;
  add_material(s, Material{});
  add_box(s, {-10, -3, -10}, {10, 7, 10}, -1, true);
  add_uv_sphere(s, {-9.0f, -2.0f, -9.0f}, 0.02f, 24, 12);
  const ModelPolygons model = extract_polygons(s);
  BspStats stats;
  const WingedPair wp = build_winged_pair(model, {}, &stats);
  EXPECT_EQ(stats.unplaced_fragments, 0u);
  EXPECT_EQ(stats.sealed_fragments, 0u);
  Pcg32 rng(7);
  auto uniform = [&](float a, float b) { return a + (b - a) * rng.next_float(); };
  for (int v = 0; v < 60; ++v) {
    const vec3 eye(uniform(-9, 9), uniform(-2, 6), uniform(-9, 9));
    const vec3 target(uniform(-9, 9), uniform(-2, 6), -10.0f);
    const Camera cam = look_at(eye, target, {0, 1, 0}, 70, 256, 192, 1e-4f, 1e3f);
    const VisibilityMap map = trace_visibility_map(wp, cam);
    double area = 0.0;
    for (const MapRegion& r : map.regions) area += region_area(r);
    EXPECT_NEAR(area, 256.0 * 192.0, 1e-6 * 256.0 * 192.0) << "view " << v;
  }
}

}  // namespace
}  // namespace proxima::visibility
