// Beam tracing: a known answer (inside a closed box every pixel sees a wall and no
// silhouette), a lone quad's silhouettes, and the Embree oracle on rooms and maze
// viewpoints at a reduced resolution (the ≥ 1024² full-path runs are `proxima visibility`).
#include "proxima/visibility/visibility_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "proxima/core/error.h"

#include "proxima/scene/visibility_models.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/oracle.h"

namespace proxima::visibility {
namespace {

Scene quad_scene(bool closed_box) {
  Scene s;
  Material m;
  add_material(s, m);
  auto quad = [&](vec3 c, vec3 u, vec3 v) {
    Mesh mesh;
    mesh.positions = {c, c + u, c + u + v, c + v};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    add_object(s, mesh, "q", 0);
  };
  quad({-1, -1, -3}, {2, 0, 0}, {0, 2, 0});
  if (closed_box) {
    quad({-1, -1, 3}, {0, 2, 0}, {2, 0, 0});
    quad({-1, -1, -3}, {0, 2, 0}, {0, 0, 6});
    quad({1, -1, -3}, {0, 0, 6}, {0, 2, 0});
    quad({-1, -1, -3}, {0, 0, 6}, {2, 0, 0});
    quad({-1, 1, -3}, {2, 0, 0}, {0, 0, 6});
  }
  return s;
}

TEST(BeamTrace, InsideAClosedBoxEveryPixelSeesAWall) {
  Scene s = quad_scene(true);
  ModelPolygons model = extract_polygons(s);
  ASSERT_EQ(model.polygons.size(), 6u);
  WingedPair wp = build_winged_pair(model);
  Camera cam = look_at({0.2f, 0.1f, 0.5f}, {0.3f, -0.2f, -3.0f}, {0, 1, 0}, 90.0f, 64, 64);
  VisibilityMap map = trace_visibility_map(wp, cam);
  EXPECT_EQ(map.stats.visible_polygons, 5u);  // a 90° view down the box misses the wall behind
  EXPECT_EQ(map.stats.silhouette_edges, 0u);  // only creases between walls
  // Regions tile the frame, so every map edge inside it has a region on both sides.
  for (const MapEdge& e : map.edges) {
    if (e.source == kImageBorder) continue;
    EXPECT_TRUE(e.region[0] != kNone && e.region[1] != kNone);
  }
  ImageU32 labels = rasterize_map(map);
  for (uint32_t id : labels.data()) ASSERT_NE(id, kNone);
  double area = 0;
  for (const MapRegion& r : map.regions)
    for (size_t i = 0; i < r.vertices.size(); ++i) {
      const dvec2 a = r.vertices[i], b = r.vertices[(i + 1) % r.vertices.size()];
      area += 0.5 * (a.x * b.y - a.y * b.x);
    }
  EXPECT_NEAR(area, 64.0 * 64.0, 1e-6);  // regions tile the image exactly
}

TEST(BeamTrace, LoneQuadSilhouettesLieOnItsBoundary) {
  Scene s = quad_scene(false);
  WingedPair wp = build_winged_pair(extract_polygons(s));
  // Inside the outer box (margin 0.25 · scale around the quad), the whole quad in view.
  Camera cam = look_at({0.05f, 0.02f, -2.4f}, {0, 0, -3}, {0, 1, 0}, 130.0f, 64, 64);
  VisibilityMap map = trace_visibility_map(wp, cam);
  EXPECT_EQ(map.stats.visible_polygons, 1u);
  // Every silhouette lies on a quad boundary edge (one opaque face around it).
  std::set<uint32_t> sources;
  for (const MapEdge& e : map.edges) {
    if (!e.silhouette) continue;
    sources.insert(e.source);
    int opaque = 0;
    uint32_t p = wp.edges[e.source].pair;
    do {
      opaque += wp.faces[wp.pairs[p].face].opaque();
      p = wp.pairs[p].spin[0];
    } while (p != wp.edges[e.source].pair);
    EXPECT_EQ(opaque, 1);
  }
  EXPECT_EQ(sources.size(), 4u);  // all four sides (needs collinear edges grouped by line)
}

TEST(BeamTrace, CameraOutsideTheBoxIsInputError) {
  WingedPair wp = build_winged_pair(extract_polygons(quad_scene(false)));
  Camera cam = look_at({0, 0, 1000}, {0, 0, 0}, {0, 1, 0}, 60.0f, 16, 16);
  EXPECT_THROW(trace_visibility_map(wp, cam), InputError);
}

TEST(BeamTrace, AgreesWithEmbreeOnRoomsAndMaze) {
  for (const Scene& scene : {make_vis_rooms(), make_vis_maze()}) {
    ModelPolygons model = extract_polygons(scene);
    WingedPair wp = build_winged_pair(model);
    RayScene rays(scene);
    const CameraPath& path = scene.camera_paths.front();
    OracleCounts total;
    for (int frame = 0; frame < path.frames; frame += path.frames / 6) {
      Camera cam = camera_at_time(path, frame_time(path, frame), 192, 192, 1e-3f, 1e4f);
      total += compare_with_ray_casts(trace_visibility_map(wp, cam), model, scene, rays, cam);
    }
    SCOPED_TRACE(scene.name);
    EXPECT_GE(total.agreement_pct(), 99.9);
    EXPECT_GE(total.interior_pct(), 99.99);
    EXPECT_EQ(total.occluded_label, 0u);
  }
}

// vcity viewpoints that had holes: frame 60, where a face of the eye's cell passes ~1 m
// from the eye (unclipped, it projected to ~1e7 px and the beam picked up a near-zero edge of
// arbitrary direction that cut a quarter of the image away), and frame 37, where clipping
// left a spike (a vertex running out along a line and back) that emptied a later beam.
TEST(BeamTrace, NoHolesOnVcityViewpointsThatHadThem) {
  const Scene scene = make_vis_vcity();
  const ModelPolygons model = extract_polygons(scene);
  const WingedPair wp = build_winged_pair(model);
  const RayScene rays(scene);
  const CameraPath& path = scene.camera_paths.front();
  for (int frame : {37, 60}) {
    SCOPED_TRACE(frame);
    const Camera cam = camera_at_time(path, frame_time(path, frame), 128, 128, 1e-3f, 1e4f);
    const VisibilityMap map = trace_visibility_map(wp, cam);
    const OracleCounts c = compare_with_ray_casts(map, model, scene, rays, cam);
    EXPECT_GE(c.agreement_pct(), 99.9);
    EXPECT_EQ(c.occluded_label, 0u);
  }
}

// Beam-plane culling skips faces before clipping; it must never change the map: regions
// (vertices, edge sources, faces), map edges and beam counts equal the unculled trace's,
// bit for bit, on viewpoints spread over the rooms, maze and vcity walks.
TEST(BeamTrace, BeamCullingNeverChangesTheMap) {
  for (const Scene& scene : {make_vis_rooms(), make_vis_maze(), make_vis_vcity()}) {
    SCOPED_TRACE(scene.name);
    const WingedPair wp = build_winged_pair(extract_polygons(scene));
    const CameraPath& path = scene.camera_paths.front();
    size_t culled_runs = 0;
    for (int frame = 0; frame < path.frames; frame += std::max(1, path.frames / 12)) {
      SCOPED_TRACE(frame);
      const Camera cam = camera_at_time(path, frame_time(path, frame), 96, 96, 1e-3f, 1e4f);
      const VisibilityMap on = trace_visibility_map(wp, cam, {.beam_culling = true});
      const VisibilityMap off = trace_visibility_map(wp, cam, {.beam_culling = false});
      ASSERT_EQ(on.regions.size(), off.regions.size());
      for (size_t r = 0; r < on.regions.size(); ++r) {
        EXPECT_EQ(on.regions[r].vertices, off.regions[r].vertices);
        EXPECT_EQ(on.regions[r].edge_source, off.regions[r].edge_source);
        EXPECT_EQ(on.regions[r].face, off.regions[r].face);
      }
      EXPECT_EQ(on.edges.size(), off.edges.size());
      EXPECT_EQ(on.stats.beams, off.stats.beams);
      EXPECT_EQ(on.stats.silhouette_edges, off.stats.silhouette_edges);
      culled_runs += on.stats.faces_culled > 0;
      EXPECT_EQ(off.stats.faces_culled, 0u);
    }
    if (scene.name != "rooms") {
      EXPECT_GT(culled_runs, 0u);  // the test exercises the culling
    }
  }
}

}  // namespace
}  // namespace proxima::visibility
