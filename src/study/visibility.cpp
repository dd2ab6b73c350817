#include "proxima/study/visibility.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/oracle.h"
#include "proxima/visibility/winged_pair_io.h"

namespace proxima::study {

namespace {

using namespace proxima::visibility;

vec3 polygon_color(uint32_t polygon) {
  if (polygon == kNone) return vec3(0.05f, 0.05f, 0.1f);
  uint64_t h = mix64(polygon);
  return {0.25f + 0.6f * float(h & 0xFF) / 255.0f, 0.25f + 0.6f * float((h >> 8) & 0xFF) / 255.0f,
          0.25f + 0.6f * float((h >> 16) & 0xFF) / 255.0f};
}

std::string svg_of(const VisibilityMap& map) {
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << map.width << "\" height=\"" << map.height
    << "\" viewBox=\"0 0 " << map.width << ' ' << map.height << "\">\n";
  for (const MapRegion& r : map.regions) {
    vec3 c = polygon_color(r.polygon);
    o << "<polygon fill=\"rgb(" << int(255 * c.x) << ',' << int(255 * c.y) << ',' << int(255 * c.z)
      << ")\" stroke=\"black\" stroke-width=\"0.3\" points=\"";
    for (const dvec2& p : r.vertices) o << p.x << ',' << p.y << ' ';
    o << "\"><title>polygon " << (r.polygon == kNone ? -1 : long(r.polygon)) << "</title></polygon>\n";
  }
  for (const MapEdge& e : map.edges) {
    if (!e.silhouette) continue;
    const dvec2 a = map.vertices[e.vertex[0]], b = map.vertices[e.vertex[1]];
    o << "<line x1=\"" << a.x << "\" y1=\"" << a.y << "\" x2=\"" << b.x << "\" y2=\"" << b.y
      << "\" stroke=\"white\" stroke-width=\"2\"/>\n";
  }
  o << "</svg>\n";
  return o.str();
}

// Regions colored by polygon, silhouettes white (pixel centers within 1 px).
ImageU8 png_of(const VisibilityMap& map) {
  const ImageU32 labels = rasterize_map(map);
  ImageU8 out(map.width, map.height, 3);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      vec3 c = polygon_color(labels.at(x, y));
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = uint8_t(255.0f * c[k]);
    }
  VisibilityMap sil = map;
  sil.edges.clear();
  for (const MapEdge& e : map.edges)
    if (e.silhouette) sil.edges.push_back(e);
  const ImageU8 mask = map_edge_mask(sil, 1.0);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      if (mask.at(x, y))
        for (int k = 0; k < 3; ++k) out.at(x, y, k) = 255;
  return out;
}

// map_NNN.svg and map_NNN.png; frame 0's under the roles map_svg and map_png.
void write_map_images(const StudyOutput& out, Results& results, int frame, const VisibilityMap& map) {
  if (!out.writes()) return;
  char name[32];
  std::snprintf(name, sizeof name, "map_%03d", frame);
  write_text_file(out.dir / (std::string(name) + ".svg"), svg_of(map));
  write_png(out.dir / (std::string(name) + ".png"), png_of(map));
  if (frame == 0) results.images = {{"map_svg", std::string(name) + ".svg"}, {"map_png", std::string(name) + ".png"}};
}

// The path the options name (pick_camera's messages name --path and --width/--height).
const CameraPath& chosen_path(const Scene& scene, const VisibilityOptions& o) {
  if (scene.camera_paths.empty()) fail_input("--scene: '" + scene.name + "' has no camera path");
  CameraChoice choice;
  choice.path = o.path.empty() ? scene.camera_paths.front().name : o.path;
  (void)pick_camera(scene, choice, o.width, o.height);
  return scene.camera_paths[size_t(find_camera_path(scene, choice.path))];
}

// --load's winged pair (checked against the model) or a new build (statistics into `bsp`).
WingedPair winged_pair_for(const ModelPolygons& model, const VisibilityOptions& o, BspStats& bsp) {
  if (o.load.empty()) return build_winged_pair(model, {}, &bsp);
  WingedPair wp = load_winged_pair(o.load);
  if (wp.polygon_count != model.polygons.size())
    fail_input("--load: " + o.load + " was built for " + std::to_string(wp.polygon_count) + " polygons, the scene has " +
               std::to_string(model.polygons.size()));
  return wp;
}

void add_build_metrics(Results& results, const Scene& scene, const ModelPolygons& model, const WingedPair& wp,
                       const BspStats& bsp) {
  auto& m = results.metrics;
  m["polygons"] = double(model.polygons.size());
  m["cells"] = double(wp.cells.size());
  m["faces"] = double(wp.faces.size());
  m["edges"] = double(wp.edges.size());
  m["vertices"] = double(wp.vertices.size());
  m["build_ms"] = bsp.build_ms;
  m["unplaced_fragments"] = double(bsp.unplaced_fragments);
  m["rejected_planes"] = double(bsp.rejected_planes);
  m["sealed_fragments"] = double(bsp.sealed_fragments);
  m["sealed_cell_extent_m"] = bsp.sealed_extent;
  results.tables.push_back({"winged pair of " + scene.name + " (Table 1)",
                            {"polygons", "cells", "faces", "edges", "vertices", "build_ms"},
                            {{m["polygons"], m["cells"], m["faces"], m["edges"], m["vertices"], m["build_ms"]}}});
}

// Sums, maxima and minima over the viewpoints.
struct ViewTotals {
  OracleCounts oracle;
  double sum_ms = 0, max_ms = 0, beams = 0, max_beams = 0, regions = 0, merged = 0, visible = 0, silhouettes = 0;
  double check_ms = 0, check_ms_max = 0, ties = 0, mismatches = 0, judged = 0;
  double worst = 100.0, worst_interior = 100.0, worst_ties = 100.0, worst_interior_ties = 100.0;
  size_t failed = 0;

  void add(const MapStats& s, const MapCheck& check) {
    sum_ms += s.ms;
    max_ms = std::max(max_ms, s.ms);
    beams += double(s.beams);
    max_beams = std::max(max_beams, double(s.beams));
    regions += double(s.regions);
    merged += double(s.merged_regions);
    visible += double(s.visible_polygons);
    silhouettes += double(s.silhouette_edges);
    ties += double(check.coplanar_ties);
    mismatches += double(check.mismatches);
    judged += double(check.samples);
    check_ms += check.ms;
    check_ms_max = std::max(check_ms_max, check.ms);
    if (!check.pass) ++failed;
  }
  void add(const OracleCounts& c) {
    oracle += c;
    worst = std::min(worst, c.agreement_pct());
    worst_interior = std::min(worst_interior, c.interior_pct());
    worst_ties = std::min(worst_ties, c.agreement_with_ties_pct());
    worst_interior_ties = std::min(worst_interior_ties, c.interior_with_ties_pct());
  }
};

void add_view_metrics(Results& results, const ViewTotals& t, int frames, bool oracle) {
  auto& m = results.metrics;
  const double n = double(frames);
  m["viewpoints"] = n;
  m["map_ms_avg"] = t.sum_ms / n;
  m["map_ms_max"] = t.max_ms;
  m["beams_avg"] = t.beams / n;
  m["beams_max"] = t.max_beams;
  m["maps_failed_selfcheck"] = double(t.failed);
  m["selfcheck_ms_avg"] = t.check_ms / n;
  m["selfcheck_ms_max"] = t.check_ms_max;
  m["selfcheck_samples"] = t.judged;
  m["selfcheck_mismatches"] = t.mismatches;
  m["selfcheck_coplanar_ties"] = t.ties;
  m["regions_avg"] = t.regions / n;
  m["merged_regions_avg"] = t.merged / n;
  m["visible_polygons_avg"] = t.visible / n;
  m["silhouette_edges_avg"] = t.silhouettes / n;
  if (!oracle) return;
  m["agreement_pct"] = t.oracle.agreement_pct();
  m["agreement_interior_pct"] = t.oracle.interior_pct();
  m["agreement_pct_worst"] = t.worst;
  m["agreement_interior_pct_worst"] = t.worst_interior;
  m["agreement_with_ties_pct"] = t.oracle.agreement_with_ties_pct();
  m["agreement_interior_with_ties_pct"] = t.oracle.interior_with_ties_pct();
  m["agreement_with_ties_pct_worst"] = t.worst_ties;
  m["agreement_interior_with_ties_pct_worst"] = t.worst_interior_ties;
  m["occluded_label_samples"] = double(t.oracle.occluded_label);
  m["oracle_samples"] = double(t.oracle.samples);
}

Table summary_table(const Scene& scene, Results& results) {
  auto& m = results.metrics;
  return {"beam tracing of " + scene.name + " (Table 2)",
          {"viewpoints", "beams_avg", "regions_avg", "visible_polygons_avg", "silhouette_edges_avg", "map_ms_avg",
           "map_ms_max", "maps_failed_selfcheck", "selfcheck_ms_avg"},
          {{m["viewpoints"], m["beams_avg"], m["regions_avg"], m["visible_polygons_avg"], m["silhouette_edges_avg"],
            m["map_ms_avg"], m["map_ms_max"], m["maps_failed_selfcheck"], m["selfcheck_ms_avg"]}}};
}

Table per_view_table(const Scene& scene, const CameraPath& path) {
  return {"visibility maps of " + scene.name + " along '" + path.name + "'",
          {"frame", "beams", "regions", "merged_regions", "visible_polygons", "silhouette_edges", "map_ms",
           "agreement_pct", "agreement_interior_pct", "agreement_interior_with_ties_pct", "selfcheck_pass",
           "selfcheck_ms"},
          {}};
}

// The map of one viewpoint; a loaded structure that cannot be traced is the file's fault.
VisibilityMap trace_map(const WingedPair& wp, const Camera& cam, const VisibilityOptions& o) {
  try {
    return trace_visibility_map(wp, cam);
  } catch (const InputError& e) {
    if (o.load.empty()) throw;
    fail_input(o.load + ": " + e.what());
  }
}

}  // namespace

void validate(const VisibilityOptions& o) {
  require_at_least(o.frames, 0, "--frames");
  require_in_range(o.selfcheck_rays, 1, 1000000, "--selfcheck-rays");
  validate_camera(look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60, o.width, o.height), "--width/--height");
}

Results run_visibility(const Scene& scene, const VisibilityOptions& o, const StudyOutput& out, Progress* progress) {
  validate(o);
  const CameraPath& path = chosen_path(scene, o);
  const int frames = o.frames > 0 ? std::min(o.frames, path.frames) : path.frames;
  Results results;
  const ModelPolygons model = extract_polygons(scene);
  BspStats bsp;
  const WingedPair wp = winged_pair_for(model, o, bsp);
  if (out.writes()) std::filesystem::create_directories(out.dir);
  if (!o.save.empty()) save_winged_pair(o.save, wp);
  add_build_metrics(results, scene, model, wp, bsp);

  // Embree rays serve the oracle and every map's self-check, on the welded geometry the map
  // is exact for (docs/visibility.md, "What the map is exact for").
  const Scene welded = welded_scene(scene, model);
  const RayScene rays(welded);
  const float far = scene_far_plane(scene);
  MapCheckOptions check_options;
  check_options.rays = o.selfcheck_rays;
  ViewTotals totals;
  Table per_view = per_view_table(scene, path);
  if (progress) progress->begin("visibility maps of " + scene.name, frames);
  for (int frame = 0; frame < frames; ++frame) {
    if (progress) progress->step("frame " + std::to_string(frame));
    const Camera cam = camera_at_time(path, frame_time(path, frame), o.width, o.height, 1e-3f, far);
    const VisibilityMap map = trace_map(wp, cam, o);
    const MapCheck check = check_visibility_map(map, model, rays, cam, check_options);
    totals.add(map.stats, check);
    if (!check.pass)
      std::fprintf(stderr, "warning: %s: visibility map of frame %d (eye %.3f %.3f %.3f) failed its self-check: %s\n",
                   scene.name.c_str(), frame, double(cam.position.x), double(cam.position.y), double(cam.position.z),
                   check.reason.c_str());
    OracleCounts c;
    if (o.oracle) totals.add(c = compare_with_ray_casts(map, model, welded, rays, cam));
    const MapStats& s = map.stats;
    per_view.rows.push_back({double(frame), double(s.beams), double(s.regions), double(s.merged_regions),
                             double(s.visible_polygons), double(s.silhouette_edges), s.ms, c.agreement_pct(),
                             c.interior_pct(), c.interior_with_ties_pct(), check.pass ? 1.0 : 0.0, check.ms});
    if (o.images) write_map_images(out, results, frame, map);
  }
  if (progress) progress->end();
  add_view_metrics(results, totals, frames, o.oracle);
  results.tables.push_back(summary_table(scene, results));
  results.tables.push_back(std::move(per_view));
  return results;
}

}  // namespace proxima::study
