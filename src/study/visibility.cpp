#include "proxima/study/visibility.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <cmath>
#include <stdexcept>
#include <vector>

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

// The winged pair's figures, in the order of kBuildNames.
constexpr const char* kBuildNames[] = {"polygons",           "cells",           "faces",
                                       "edges",              "vertices",        "build_ms",
                                       "unplaced_fragments", "rejected_planes", "sealed_fragments",
                                       "sealed_cell_extent_m"};
constexpr size_t kBuildFigures = std::size(kBuildNames);

std::vector<double> build_figures(const ModelPolygons& model, const WingedPair& wp, const BspStats& bsp) {
  return {double(model.polygons.size()), double(wp.cells.size()),      double(wp.faces.size()),
          double(wp.edges.size()),         double(wp.vertices.size()),   bsp.build_ms,
          double(bsp.unplaced_fragments),  double(bsp.rejected_planes), double(bsp.sealed_fragments),
          bsp.sealed_extent};
}

void add_build_metrics(Results& results, const Scene& scene, const std::vector<double>& build) {
  auto& m = results.metrics;
  for (size_t i = 0; i < kBuildFigures; ++i) m[kBuildNames[i]] = build[i];
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

// One viewpoint's figures: its map's statistics, self-check and oracle counts.
enum ViewField { kFrame, kBeams, kRegions, kMerged, kVisible, kSilhouettes, kMapMs, kPass, kCheckMs, kTies,
                 kMismatches, kJudged, kSamples, kAgree, kInterior, kInteriorAgree, kOccluded, kOracleTies,
                 kInteriorTies, kViewFields };
using ViewFigures = std::array<double, kViewFields>;

ViewFigures view_figures(int frame, const MapStats& s, const MapCheck& check, const OracleCounts& c) {
  ViewFigures v{};
  v[kFrame] = double(frame);
  v[kBeams] = double(s.beams);
  v[kRegions] = double(s.regions);
  v[kMerged] = double(s.merged_regions);
  v[kVisible] = double(s.visible_polygons);
  v[kSilhouettes] = double(s.silhouette_edges);
  v[kMapMs] = s.ms;
  v[kPass] = check.pass ? 1.0 : 0.0;
  v[kCheckMs] = check.ms;
  v[kTies] = double(check.coplanar_ties);
  v[kMismatches] = double(check.mismatches);
  v[kJudged] = double(check.samples);
  const size_t* counts[] = {&c.samples, &c.agree, &c.interior, &c.interior_agree, &c.occluded_label, &c.ties,
                            &c.interior_ties};
  for (int k = 0; k < 7; ++k) v[size_t(kSamples + k)] = double(*counts[k]);
  return v;
}

// A count stored in a double (exact up to 2⁵³). The figures may come from a frame part's
// bytes (sweep/frame_parts.h), so anything else is refused before the conversion.
size_t count(double v) {
  if (!(v >= 0.0 && v <= 9007199254740992.0 && v == std::floor(v)))
    throw std::runtime_error("visibility: a frame figure that is not a count");
  return size_t(v);
}

// A viewpoint into the totals and the per-view table (counts are exact in a double).
void add_view(const ViewFigures& v, bool oracle, ViewTotals& totals, Table& per_view) {
  MapStats s;
  s.beams = count(v[kBeams]);
  s.regions = count(v[kRegions]);
  s.merged_regions = count(v[kMerged]);
  s.visible_polygons = count(v[kVisible]);
  s.silhouette_edges = count(v[kSilhouettes]);
  s.ms = v[kMapMs];
  MapCheck check;
  check.pass = v[kPass] != 0.0;
  check.ms = v[kCheckMs];
  check.coplanar_ties = count(v[kTies]);
  check.mismatches = count(v[kMismatches]);
  check.samples = count(v[kJudged]);
  totals.add(s, check);
  OracleCounts c;
  size_t* counts[] = {&c.samples, &c.agree, &c.interior, &c.interior_agree, &c.occluded_label, &c.ties,
                      &c.interior_ties};
  for (int k = 0; k < 7; ++k) *counts[k] = count(v[size_t(kSamples + k)]);
  if (oracle) totals.add(c);
  per_view.rows.push_back({v[kFrame], double(s.beams), double(s.regions), double(s.merged_regions),
                           double(s.visible_polygons), double(s.silhouette_edges), s.ms, c.agreement_pct(),
                           c.interior_pct(), c.interior_with_ties_pct(), v[kPass], check.ms});
}

// The frames of the chosen path the run covers.
int run_frames(const VisibilityOptions& o, const CameraPath& path) {
  return o.frames > 0 ? std::min(o.frames, path.frames) : path.frames;
}

// Frames [first, last): the winged pair built (or loaded, and saved when `save`), each map
// traced, checked and compared; the build's figures into `build`, each viewpoint's into
// `views`, the map images into `out` and `results`.
void trace_frames(const Scene& scene, const VisibilityOptions& o, int first, int last, bool save,
                  const StudyOutput& out, Progress* progress, std::vector<double>& build,
                  std::vector<ViewFigures>& views, Results& results) {
  const CameraPath& path = chosen_path(scene, o);
  const ModelPolygons model = extract_polygons(scene);
  BspStats bsp;
  const WingedPair wp = winged_pair_for(model, o, bsp);
  if (out.writes()) std::filesystem::create_directories(out.dir);
  if (save && !o.save.empty()) save_winged_pair(o.save, wp);
  build = build_figures(model, wp, bsp);

  // Embree rays serve the oracle and every map's self-check, on the welded geometry the map
  // is exact for (docs/visibility.md, "What the map is exact for").
  const Scene welded = welded_scene(scene, model);
  const RayScene rays(welded);
  const float far = scene_far_plane(scene);
  MapCheckOptions check_options;
  check_options.rays = o.selfcheck_rays;
  if (progress) progress->begin("visibility maps of " + scene.name, last - first);
  for (int frame = first; frame < last; ++frame) {
    if (progress) progress->step("frame " + std::to_string(frame));
    const Camera cam = camera_at_time(path, frame_time(path, frame), o.width, o.height, 1e-3f, far);
    const VisibilityMap map = trace_map(wp, cam, o);
    const MapCheck check = check_visibility_map(map, model, rays, cam, check_options);
    if (!check.pass)
      std::fprintf(stderr, "warning: %s: visibility map of frame %d (eye %.3f %.3f %.3f) failed its self-check: %s\n",
                   scene.name.c_str(), frame, double(cam.position.x), double(cam.position.y), double(cam.position.z),
                   check.reason.c_str());
    OracleCounts c;
    if (o.oracle) c = compare_with_ray_casts(map, model, welded, rays, cam);
    views.push_back(view_figures(frame, map.stats, check, c));
    if (o.images) write_map_images(out, results, frame, map);
  }
  if (progress) progress->end();
}

// The run's metrics and tables from the build's and every viewpoint's figures.
void add_results(const Scene& scene, const VisibilityOptions& o, const std::vector<double>& build,
                 const std::vector<ViewFigures>& views, Results& results) {
  add_build_metrics(results, scene, build);
  ViewTotals totals;
  Table per_view = per_view_table(scene, chosen_path(scene, o));
  for (const ViewFigures& v : views) add_view(v, o.oracle, totals, per_view);
  add_view_metrics(results, totals, int(views.size()), o.oracle);
  results.tables.push_back(summary_table(scene, results));
  results.tables.push_back(std::move(per_view));
}

}  // namespace

void validate(const VisibilityOptions& o) {
  require_at_least(o.frames, 0, "--frames");
  require_in_range(o.selfcheck_rays, 1, 1000000, "--selfcheck-rays");
  validate_camera(look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60, o.width, o.height), "--width/--height");
}

Results run_visibility(const Scene& scene, const VisibilityOptions& o, const StudyOutput& out, Progress* progress) {
  validate(o);
  const int frames = run_frames(o, chosen_path(scene, o));
  Results results;
  std::vector<double> build;
  std::vector<ViewFigures> views;
  trace_frames(scene, o, 0, frames, true, out, progress, build, views, results);
  add_results(scene, o, build, views, results);
  return results;
}

Results run_visibility_part(const Scene& scene, const VisibilityOptions& o, const FramePart& part,
                            const StudyOutput& out, FrameFigures& figures, Progress* progress) {
  validate(o);
  const auto [first, last] = frame_span(part, run_frames(o, chosen_path(scene, o)));
  Results results;
  std::vector<double> build;
  std::vector<ViewFigures> views;
  // Part 0 gives the winged pair's figures (and saves it); a later part without frames
  // builds nothing.
  if (part.index == 0 || first < last)
    trace_frames(scene, o, first, last, part.index == 0, out, progress, build, views, results);
  figures.series.assign(kBuildFigures + kViewFields, {});
  if (part.index == 0)
    for (size_t i = 0; i < kBuildFigures; ++i) figures.series[i].push_back(build[i]);
  for (const ViewFigures& v : views)
    for (size_t i = 0; i < kViewFields; ++i) figures.series[kBuildFigures + i].push_back(v[i]);
  return results;
}

Results visibility_results(const Scene& scene, const VisibilityOptions& o, const FrameFigures& figures) {
  validate(o);
  const auto& f = figures.series;
  bool shaped = f.size() == kBuildFigures + kViewFields;
  for (size_t i = 0; shaped && i < f.size(); ++i)
    shaped = f[i].size() == (i < kBuildFigures ? 1 : f[kBuildFigures].size());
  if (!shaped) throw std::runtime_error("visibility: frame figures of the wrong shape");
  std::vector<double> build(kBuildFigures);
  for (size_t i = 0; i < kBuildFigures; ++i) build[i] = f[i][0];
  std::vector<ViewFigures> views(f[kBuildFigures].size());
  for (size_t k = 0; k < views.size(); ++k)
    for (size_t i = 0; i < kViewFields; ++i) views[k][i] = f[kBuildFigures + i][k];
  Results results;
  add_results(scene, o, build, views, results);
  return results;
}

}  // namespace proxima::study
