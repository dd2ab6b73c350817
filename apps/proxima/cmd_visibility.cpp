// `proxima visibility`: exact visibility maps (Funkhouser's BSP → winged pair → beam tracing)
// along a camera path, with build statistics (Table 1 shape), per-viewpoint statistics
// (Table 2 shape), the Embree oracle, the self-check of every map (visibility/map_check.h)
// and an SVG + PNG of every map.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "command.h"
#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/scene/load.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/map_check.h"
#include "proxima/visibility/oracle.h"
#include "proxima/visibility/winged_pair_io.h"

namespace proxima::cli {

namespace {

using namespace proxima::visibility;

// Exit code of `--strict` when at least one map failed its self-check (results are written).
constexpr int kExitSelfCheck = 3;

struct VisibilityFlags {
  CommonOptions common;
  std::string path;
  int floors = 0;       // building only; 0 = the default 5
  int frames = 0;       // viewpoints: 0 = every frame of the path
  bool oracle = true;
  bool images = true;
  bool strict = false;  // exit kExitSelfCheck when a map fails its self-check
  int selfcheck_rays = MapCheckOptions{}.rays;
  std::string load, save;
};

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

}  // namespace

Command register_visibility(CLI::App& root) {
  static VisibilityFlags f;
  auto* app = root.add_subcommand("visibility", "exact visibility maps by beam tracing a BSP cell complex, vs Embree");
  add_scene_flag(app, f.common, "rooms");
  f.common.width = f.common.height = 1024;
  add_size_flags(app, f.common);
  add_threads_flag(app, f.common);
  add_out_flag(app, f.common, true);
  app->add_option("--path", f.path, "camera path, by index or name (default: the first)");
  app->add_option("--floors", f.floors, "floors of the `building` scene (default 5)");
  app->add_option("--frames", f.frames, "viewpoints: the first N frames of the path (default: all)");
  app->add_flag("!--no-oracle", f.oracle, "skip the Embree comparison");
  app->add_flag("!--no-images", f.images, "skip the per-viewpoint SVG and PNG");
  app->add_option("--load", f.load, "winged-pair file to use instead of building one");
  app->add_option("--save", f.save, "write the winged pair built to this file");
  app->add_option("--selfcheck-rays", f.selfcheck_rays, "Embree rays of each map's self-check (default 128)");
  app->add_flag("--strict", f.strict, "exit 3 when any map fails its self-check (results are still written)");

  return {app, [] {
            if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
            if (f.frames < 0) fail_input("--frames: must be ≥ 0");
            if (f.selfcheck_rays < 1 || f.selfcheck_rays > 1000000) fail_input("--selfcheck-rays: must be in 1..1000000");
            if (f.floors != 0 && f.common.scene != "building")
              fail_input("--floors: only the `building` scene has floors");
            ThreadLimit limit(f.common.threads);
            Scene scene = f.floors != 0 ? make_vis_building(f.floors) : load_scene(f.common.scene);
            if (scene.camera_paths.empty()) fail_input("--scene: '" + scene.name + "' has no camera path");
            CameraChoice choice;
            choice.path = f.path.empty() ? scene.camera_paths.front().name : f.path;
            Camera probe = pick_camera(scene, choice, f.common.width, f.common.height);  // validates flags
            (void)probe;
            const CameraPath* path = nullptr;
            for (const auto& p : scene.camera_paths)
              if (p.name == choice.path || std::to_string(&p - scene.camera_paths.data()) == choice.path) path = &p;
            const int frames = f.frames > 0 ? std::min(f.frames, path->frames) : path->frames;
            Results results;
            results.command = command_line();
            results.threads = active_threads();
            ModelPolygons model = extract_polygons(scene);
            BspStats bsp;
            WingedPair wp;
            if (!f.load.empty()) {
              wp = load_winged_pair(f.load);
              if (wp.polygon_count != model.polygons.size())
                fail_input("--load: " + f.load + " was built for " + std::to_string(wp.polygon_count) +
                           " polygons, the scene has " + std::to_string(model.polygons.size()));
            } else {
              wp = build_winged_pair(model, {}, &bsp);
            }
            auto out = prepare_out_dir(f.common.out);  // after the --load file is read: nothing half-written
            if (!f.save.empty()) save_winged_pair(f.save, wp);
            auto& m = results.metrics;
            m["polygons"] = double(model.polygons.size());
            m["cells"] = double(wp.cells.size());
            m["faces"] = double(wp.faces.size());
            m["edges"] = double(wp.edges.size());
            m["vertices"] = double(wp.vertices.size());
            m["build_ms"] = bsp.build_ms;
            m["unplaced_fragments"] = double(bsp.unplaced_fragments);
            m["rejected_planes"] = double(bsp.rejected_planes);
            results.tables.push_back({"winged pair of " + scene.name + " (Table 1)",
                                      {"polygons", "cells", "faces", "edges", "vertices", "build_ms"},
                                      {{m["polygons"], m["cells"], m["faces"], m["edges"], m["vertices"], m["build_ms"]}}});

            // Embree rays serve the oracle and every map's self-check.
            const RayScene rays(scene);
            const float far = scene_far_plane(scene);
            OracleCounts total;
            double sum_ms = 0, max_ms = 0, beams = 0, regions = 0, merged = 0, visible = 0, silhouettes = 0;
            double max_beams = 0, check_ms = 0, check_ms_max = 0, worst = 100.0, worst_interior = 100.0;
            double worst_ties = 100.0, worst_interior_ties = 100.0;
            size_t failed = 0;
            double ties = 0, mismatches = 0, judged = 0;
            Table per_view{"visibility maps of " + scene.name + " along '" + path->name + "'",
                           {"frame", "beams", "regions", "merged_regions", "visible_polygons", "silhouette_edges", "map_ms",
                            "agreement_pct", "agreement_interior_pct", "agreement_interior_with_ties_pct", "selfcheck_pass",
                            "selfcheck_ms"},
                           {}};
            for (int frame = 0; frame < frames; ++frame) {
              Camera cam = camera_at_time(*path, frame_time(*path, frame), f.common.width, f.common.height, 1e-3f, far);
              VisibilityMap map;
              try {
                map = trace_visibility_map(wp, cam);
              } catch (const InputError& e) {
                if (f.load.empty()) throw;
                fail_input(f.load + ": " + e.what());  // a loaded structure that cannot be traced
              }
              const MapStats& s = map.stats;
              sum_ms += s.ms;
              max_ms = std::max(max_ms, s.ms);
              beams += double(s.beams);
              max_beams = std::max(max_beams, double(s.beams));
              regions += double(s.regions);
              merged += double(s.merged_regions);
              visible += double(s.visible_polygons);
              silhouettes += double(s.silhouette_edges);
              MapCheckOptions check_options;
              check_options.rays = f.selfcheck_rays;
              const MapCheck check = check_visibility_map(map, model, rays, cam, check_options);
              ties += double(check.coplanar_ties);
              mismatches += double(check.mismatches);
              judged += double(check.samples);
              check_ms += check.ms;
              check_ms_max = std::max(check_ms_max, check.ms);
              if (!check.pass) {
                ++failed;
                std::fprintf(stderr, "warning: %s: visibility map of frame %d (eye %.3f %.3f %.3f) failed its self-check: %s\n",
                             scene.name.c_str(), frame, double(cam.position.x), double(cam.position.y),
                             double(cam.position.z), check.reason.c_str());
              }
              OracleCounts c;
              if (f.oracle) {
                c = compare_with_ray_casts(map, model, scene, rays, cam);
                total += c;
                worst = std::min(worst, c.agreement_pct());
                worst_interior = std::min(worst_interior, c.interior_pct());
                worst_ties = std::min(worst_ties, c.agreement_with_ties_pct());
                worst_interior_ties = std::min(worst_interior_ties, c.interior_with_ties_pct());
              }
              per_view.rows.push_back({double(frame), double(s.beams), double(s.regions), double(s.merged_regions),
                                       double(s.visible_polygons), double(s.silhouette_edges), s.ms,
                                       c.agreement_pct(), c.interior_pct(), c.interior_with_ties_pct(), check.pass ? 1.0 : 0.0,
                                       check.ms});
              if (f.images) {
                char name[32];
                std::snprintf(name, sizeof name, "map_%03d", frame);
                write_text_file(out / (std::string(name) + ".svg"), svg_of(map));
                write_png(out / (std::string(name) + ".png"), png_of(map));
                if (frame == 0) results.images = {{"map_svg", std::string(name) + ".svg"}, {"map_png", std::string(name) + ".png"}};
              }
            }
            const double n = double(frames);
            m["viewpoints"] = n;
            m["map_ms_avg"] = sum_ms / n;
            m["map_ms_max"] = max_ms;
            m["beams_avg"] = beams / n;
            m["beams_max"] = max_beams;
            m["maps_failed_selfcheck"] = double(failed);
            m["selfcheck_ms_avg"] = check_ms / n;
            m["selfcheck_ms_max"] = check_ms_max;
            m["selfcheck_samples"] = judged;
            m["selfcheck_mismatches"] = mismatches;
            m["selfcheck_coplanar_ties"] = ties;
            m["regions_avg"] = regions / n;
            m["merged_regions_avg"] = merged / n;
            m["visible_polygons_avg"] = visible / n;
            m["silhouette_edges_avg"] = silhouettes / n;
            if (f.oracle) {
              m["agreement_pct"] = total.agreement_pct();
              m["agreement_interior_pct"] = total.interior_pct();
              m["agreement_pct_worst"] = worst;
              m["agreement_interior_pct_worst"] = worst_interior;
              m["agreement_with_ties_pct"] = total.agreement_with_ties_pct();
              m["agreement_interior_with_ties_pct"] = total.interior_with_ties_pct();
              m["agreement_with_ties_pct_worst"] = worst_ties;
              m["agreement_interior_with_ties_pct_worst"] = worst_interior_ties;
              m["occluded_label_samples"] = double(total.occluded_label);
              m["oracle_samples"] = double(total.samples);
            }
            results.tables.push_back({"beam tracing of " + scene.name + " (Table 2)",
                                      {"viewpoints", "beams_avg", "regions_avg", "visible_polygons_avg",
                                       "silhouette_edges_avg", "map_ms_avg", "map_ms_max", "maps_failed_selfcheck",
                                       "selfcheck_ms_avg"},
                                      {{n, m["beams_avg"], m["regions_avg"], m["visible_polygons_avg"],
                                        m["silhouette_edges_avg"], m["map_ms_avg"], m["map_ms_max"],
                                        m["maps_failed_selfcheck"], m["selfcheck_ms_avg"]}}});
            results.tables.push_back(std::move(per_view));
            publish_results(out, results);
            if (failed > 0)
              std::fprintf(stderr, "warning: %s: %zu of %d visibility maps failed their self-check%s\n", scene.name.c_str(),
                           failed, frames, f.strict ? "" : " (--strict makes this exit 3)");
            return f.strict && failed > 0 ? kExitSelfCheck : 0;
          }};
}

}  // namespace proxima::cli
