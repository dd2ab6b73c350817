// Degenerate input for the BSP and the beam tracer (robustness): duplicate,
// coplanar overlapping, zero-area, sliver and T-junction polygons, and viewpoints lying on
// a polygon's plane (a BSP face). Nothing may crash or loop, every cell stays closed
// (V − E + F = 2), and inside a closed room every pixel of the map shows a polygon that
// Embree agrees with (up to which of two coplanar overlapping polygons is named).
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/visibility_map.h"
#include "visibility/hand_built_scene.h"

namespace proxima::visibility {
namespace {

// A closed 10 m room around the origin, walls facing in.
Scene room() {
  Scene s;
  add_material(s, Material{});
  const vec3 o(0.0f);
  add_quad(s, {-5, -5, -5}, {10, 0, 0}, {0, 10, 0}, o);
  add_quad(s, {-5, -5, 5}, {10, 0, 0}, {0, 10, 0}, o);
  add_quad(s, {-5, -5, -5}, {0, 0, 10}, {0, 10, 0}, o);
  add_quad(s, {5, -5, -5}, {0, 0, 10}, {0, 10, 0}, o);
  add_quad(s, {-5, -5, -5}, {10, 0, 0}, {0, 0, 10}, o);
  add_quad(s, {-5, 5, -5}, {10, 0, 0}, {0, 0, 10}, o);
  return s;
}

bool coplanar(const ModelPolygons& m, uint32_t a, uint32_t b) {
  const Plane& p = m.polygons[a].plane;
  const Plane& q = m.polygons[b].plane;
  return glm::dot(p.normal, q.normal) > 1.0 - 1e-9 && std::abs(p.offset - q.offset) < 1e-6 * m.scale;
}

// Builds, checks each cell's Euler characteristic, traces `cameras` and compares with Embree.
void expect_robust(const Scene& s, const std::vector<Camera>& cameras, const std::string& what) {
  SCOPED_TRACE(what);
  const ModelPolygons model = extract_polygons(s);
  BspStats stats;
  const WingedPair wp = build_winged_pair(model, {}, &stats);
  ASSERT_EQ(wp.loop_offset.size(), wp.faces.size() + 1) << "finalize failed";
  for (uint32_t c = 0; c < wp.cells.size(); ++c) {
    std::set<uint32_t> verts, edges;
    for (uint32_t f : wp.faces_of_cell(c)) {
      for (uint32_t v : wp.face_vertices(f)) verts.insert(v);
      for (uint32_t e : wp.face_edges(f)) edges.insert(e);
    }
    ASSERT_EQ(long(verts.size()) - long(edges.size()) + long(wp.faces_of_cell(c).size()), 2) << "cell " << c;
  }
  const RayScene rays(s);
  for (const Camera& cam : cameras) {
    SCOPED_TRACE("camera at " + std::to_string(cam.position.x) + ", " + std::to_string(cam.position.y) + ", " +
                 std::to_string(cam.position.z));
    const VisibilityMap map = trace_visibility_map(wp, cam);
    const ImageU32 labels = rasterize_map(map);
    const ItemBuffer item = trace_item_buffer(s, rays, cam);
    size_t holes = 0, agree = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const uint32_t label = labels.at(x, y), tri = item.triangle.at(x, y);
        holes += label == kNone;
        if (tri == kNoTriangle || label == kNone) continue;
        const uint32_t truth = model.triangle_polygon[tri];
        agree += label == truth || coplanar(model, label, truth);
      }
    EXPECT_EQ(holes, 0u);
    EXPECT_GE(double(agree), 0.999 * cam.width * cam.height);
  }
}

std::vector<Camera> views(vec3 eye) {
  return {look_at(eye, {0, 0, -5}, {0, 1, 0}, 90.0f, 96, 96), look_at(eye, {4, -3, 0}, {0, 1, 0}, 70.0f, 96, 96)};
}

TEST(VisibilityDegenerate, DuplicatePolygons) {
  Scene s = room();
  for (int k = 0; k < 2; ++k) add_quad(s, {-1, -1, -2}, {2, 0, 0}, {0, 2, 0}, {0, 0, 5});
  expect_robust(s, views({0.3f, 0.2f, 3.0f}), "duplicate quads");
}

TEST(VisibilityDegenerate, CoplanarOverlappingPolygons) {
  Scene s = room();
  add_quad(s, {-1, -1, -2}, {2, 0, 0}, {0, 2, 0}, {0, 0, 5});
  add_quad(s, {-0.5f, -0.3f, -2}, {2, 0, 0}, {0, 2, 0}, {0, 0, 5});
  expect_robust(s, views({0.3f, 0.2f, 3.0f}), "overlapping coplanar quads");
}

TEST(VisibilityDegenerate, ZeroAreaAndSliverTriangles) {
  Scene s = room();
  add_quad(s, {-1, -1, -2}, {2, 0, 0}, {0, 2, 0}, {0, 0, 5});
  add_mesh(s, {{-2, 0, -1}, {0, 0, -1}, {2, 0, -1}}, {{0, 1, 2}});          // collinear
  add_mesh(s, {{-2, 1, -1}, {2, 1, -1}, {0, 1 + 1e-7f, -1}}, {{0, 1, 2}});  // sliver
  add_mesh(s, {{1, 1, 1}, {1, 1, 1}, {1, 2, 1}}, {{0, 1, 2}});              // repeated vertex
  expect_robust(s, views({0.3f, 0.2f, 3.0f}), "zero-area triangles");
}

TEST(VisibilityDegenerate, TJunctions) {
  Scene s = room();
  add_quad(s, {-2, -1, -2}, {4, 0, 0}, {0, 1, 0}, {0, 0, 5});
  add_quad(s, {-2, 0, -2}, {1.5f, 0, 0}, {0, 1, 0}, {0, 0, 5});
  add_quad(s, {-0.5f, 0, -2}, {2.5f, 0, 0}, {0, 1, 0}, {0, 0, 5});
  add_quad(s, {-0.5f, -1, -2}, {0, 0, 1.5f}, {0, 2, 0}, {5, 0, 0});  // a fin on the T vertex line
  expect_robust(s, views({0.3f, 0.2f, 3.0f}), "T-junctions");
}

TEST(VisibilityDegenerate, ViewpointOnAPolygonPlane) {
  Scene s = room();
  add_quad(s, {-1, -1, -2}, {2, 0, 0}, {0, 2, 0}, {0, 0, 5});
  add_quad(s, {-3, -5, 1}, {0, 0, 2}, {0, 4, 0}, {5, 0, 0});
  // On the quad's plane z = −2 beside it, on the fin's plane x = −3, and on a wall.
  std::vector<Camera> cams = views({2.5f, 0.0f, -2.0f});
  for (const Camera& c : views({-3.0f, 0.5f, 3.0f})) cams.push_back(c);
  for (const Camera& c : views({4.0f, 0.0f, 5.0f - 1e-7f})) cams.push_back(c);
  expect_robust(s, cams, "viewpoint on a plane");
}

}  // namespace
}  // namespace proxima::visibility
