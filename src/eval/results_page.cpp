// results_page (eval/results_page.h): docs/RESULTS.md from the merged results.json of
// scripts/results.sh. Which metric each cell shows and the papers' own figures are written
// here, once; every number comes from the input, formatted with fixed decimals.
#include "proxima/eval/results_page.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <regex>
#include <sstream>

namespace proxima {

namespace {

// A number with `decimals` decimals; "—" when it was not measured (NaN or missing).
std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "—";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string times(double v) { return std::isfinite(v) ? fixed(v, 2) + "×" : "—"; }

// "a–b" over the finite values (one value alone when they round alike).
std::string span(std::vector<double> values, int decimals) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
               values.end());
  if (values.empty()) return "—";
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const std::string a = fixed(*lo, decimals), b = fixed(*hi, decimals);
  return a == b ? a : a + "–" + b;
}

// The least finite value; NaN when there is none.
double lowest(const std::vector<double>& values) {
  double low = std::nan("");
  for (double v : values)
    if (std::isfinite(v) && !(v >= low)) low = v;
  return low;
}

using Row = std::vector<std::string>;

std::string markdown(const Row& header, const std::vector<Row>& rows) {
  std::string s = "|";
  for (const std::string& h : header) s += " " + h + " |";
  s += "\n|";
  for (size_t i = 0; i < header.size(); ++i) s += " --- |";
  s += "\n";
  for (const Row& r : rows) {
    s += "|";
    for (const std::string& c : r) s += " " + c + " |";
    s += "\n";
  }
  return s;
}

class Page {
 public:
  explicit Page(const Results& r) : r_(r) {}

  // A metric of the merged results; NaN (and listed as missing) when the input lacks it.
  double m(const std::string& key) {
    const auto it = r_.metrics.find(key);
    if (it != r_.metrics.end()) return it->second;
    if (std::find(missing_.begin(), missing_.end(), key) == missing_.end()) missing_.push_back(key);
    return std::nan("");
  }

  // The commands of the named sections (merge_results' run sections and the demo's), one
  // shell block.
  std::string commands(std::initializer_list<const char*> ids) const {
    std::string s = "```sh\n";
    for (const char* id : ids)
      for (const Section& sec : r_.sections)
        if (sec.id == id)
          for (const std::string& c : sec.commands) s += c + "\n";
    return s + "```\n";
  }

  // The first "WxH" in the title of the table whose title starts with `prefix`; "" if none.
  std::string table_size(const std::string& prefix) const {
    static const std::regex size(R"((\d+)x(\d+))");
    for (const Table& t : r_.tables) {
      std::smatch match;
      if (t.title.rfind(prefix, 0) == 0 && std::regex_search(t.title, match, size)) return match.str(0);
    }
    return "";
  }

  const Results& results() const { return r_; }
  std::vector<std::string> missing() const { return missing_; }

 private:
  const Results& r_;
  std::vector<std::string> missing_;
};

// ---- one part of the page per technique: the summary row and the detail ----------------

struct Part {
  Row summary;         // technique, setting, error, paper's error, speed, paper's speed
  std::string detail;  // "## ..." section
};

const char* const kSamplingScenes[] = {"nest", "grass", "city", "tree"};
// Thesis Table 4: available samples per output frame, % (conventional, NRR, peeling).
const char* const kSamplingThesis[] = {"90 / 93 / 92", "86 / 96 / 93", "97 / 98 / 96", "55 / 59 / 55"};
const char* const kSamplingMethods[] = {"conventional", "nrr_pixel", "peeling"};
const char* const kShadowMethods[] = {"nrr", "conventional", "peeling"};
// Thesis Table 9, city at 1024² reference images: mean intensity · visibility error.
const char* const kShadowThesis[] = {"1.60 · 2.07", "3.46 · 3.64", "11.3 · 12.6"};
const char* const kEnvmapScenes[] = {"room-reflector", "room-car", "room-parallax"};
const char* const kEnvmapMethods[] = {"envmap", "rectified", "average", "layered"};
const char* const kReflectPaths[] = {"living-room_walk", "bathroom_walk"};
const char* const kReflectPathNames[] = {"living-room / walk", "bathroom / walk"};
const char* const kVisibilityModels[] = {"rooms", "maze", "arena", "vcity", "floor", "level-medium"};
// Funkhouser's Table 1 polygon counts of the models ours stand in for.
const char* const kVisibilityPaperPolygons[] = {"20", "310", "665", "1125", "1772", "—"};
const char* const kViewerTechniques[] = {"reference", "envmap", "rectified", "cluster", "temporal", "shadows"};

Part reference_part(Page& p) {
  const std::string size = p.table_size("bench_trace: ");
  const double mrays = p.m("bench_trace_primary_mrays_s");
  std::vector<Row> rows;
  for (const char* suffix : {"_1t", ""})
    rows.push_back({suffix[0] ? "1" : std::to_string(p.results().threads),
                    fixed(p.m(std::string("bench_trace_bvh_build_ms") + suffix), 1),
                    fixed(p.m(std::string("bench_trace_primary_mrays_s") + suffix), 2),
                    fixed(p.m(std::string("bench_trace_reflection_mrays_s") + suffix), 2)});
  std::string d = "## Reference renderer (Embree)\n\n";
  d += "What every technique is measured against. `proxima bench trace` on living-room (" + size + ", camera "
       "overview, " + fixed(p.m("bench_trace_triangles"), 0) + " triangles, " +
       fixed(p.m("bench_trace_reflection_rays"), 0) + " mirror rays from reflective hits):\n\n";
  d += markdown({"threads", "BVH build ms", "primary Mrays/s", "reflection Mrays/s"}, rows);
  d += "\nReference renders of the demo (512², 2×2 samples per pixel): cornell " +
       fixed(p.m("demo_cornell_render_ms"), 0) + " ms, living-room " + fixed(p.m("demo_living_room_render_ms"), 0) +
       " ms.\n\n";
  d += p.commands({"bench_trace", "demo-reference"});
  return {{"Reference renderer (Embree)", "living-room " + size, "— (the reference)", "—",
           fixed(mrays, 2) + " Mrays/s primary", "—"},
          d};
}

Part raster_part(Page& p) {
  const std::string size = p.table_size("bench_raster: ");
  const bool same_image = !size.empty() && size == p.table_size("bench_trace: ");
  double pixels = std::nan("");
  if (same_image) {
    const size_t x = size.find('x');
    pixels = std::stod(size.substr(0, x)) * std::stod(size.substr(x + 1));
  }
  // Embree's item buffer of the same image: one primary ray per pixel.
  const auto embree_ms = [&](const char* suffix) {
    return pixels / (p.m(std::string("bench_trace_primary_mrays_s") + suffix) * 1e3);
  };
  std::vector<Row> rows;
  for (const char* suffix : {"_1t", ""}) {
    const double ms = p.m(std::string("bench_raster_raster_ms_depth_id") + suffix);
    rows.push_back({suffix[0] ? "1" : std::to_string(p.results().threads), fixed(ms, 1),
                    fixed(p.m(std::string("bench_raster_raster_ms_gbuffer") + suffix), 1), fixed(embree_ms(suffix), 1),
                    times(embree_ms(suffix) / ms), fixed(p.m(std::string("bench_raster_llvmpipe_ms_depth_id") + suffix), 1),
                    times(p.m(std::string("bench_raster_speedup_vs_llvmpipe") + suffix))});
  }
  const double agree = p.m("demo_id_agreement_pct"), ties = p.m("demo_id_agreement_with_ties_pct");
  const double speed = embree_ms("") / p.m("bench_raster_raster_ms_depth_id");
  std::string d = "## Software rasterizer\n\n";
  d += "Triangle ids rasterized vs Embree's item buffer at every pixel center, 512², every built-in camera: "
       "the worst camera agrees at " + fixed(agree, 3) + " % of the pixels, " + fixed(ties, 3) +
       " % counting ties (pixel centers on an edge two triangles share, coincident surfaces).\n\n";
  d += "Speed on living-room " + size + " (camera overview): the depth + id pass against Embree tracing one "
       "primary ray per pixel (Mrays/s of the reference section: a separate run, not side by side" +
       (same_image ? "" : "; NOT the same image size: no ratio") + ") and against Mesa llvmpipe (— when its "
       "harness is not built):\n\n";
  d += markdown({"threads", "depth + id ms", "G-buffer ms", "Embree primary rays ms", "speed vs Embree",
                 "llvmpipe ms", "speed vs llvmpipe"},
                rows);
  d += "\n" + p.commands({"demo-raster", "bench_raster"});
  return {{"Software rasterizer", "every built-in camera 512²; speed on living-room " + size,
           "ids agree at ≥ " + fixed(agree, 2) + " % of pixels (" + fixed(ties, 2) + " % with ties)", "—",
           times(speed) + " Embree primary rays", "—"},
          d};
}

Part sampling_part(Page& p) {
  std::vector<Row> rows;
  std::vector<double> nrr_avail, conv_avail, nrr_over_conv;
  for (size_t i = 0; i < 4; ++i) {
    const std::string s = std::string("demo_sampling_") + kSamplingScenes[i] + "_";
    double avail[3], ms[3];
    for (int k = 0; k < 3; ++k) {
      avail[k] = p.m(s + kSamplingMethods[k] + "_available_avg_pct");
      ms[k] = p.m(s + kSamplingMethods[k] + "_time_ms");
    }
    conv_avail.push_back(avail[0]);
    nrr_avail.push_back(avail[1]);
    nrr_over_conv.push_back(ms[1] / ms[0]);
    rows.push_back({kSamplingScenes[i], fixed(avail[0], 1) + " / " + fixed(avail[1], 1) + " / " + fixed(avail[2], 1),
                    kSamplingThesis[i], fixed(ms[0], 1) + " / " + fixed(ms[1], 1) + " / " + fixed(ms[2], 1),
                    times(ms[1] / ms[0]), times(ms[1] / ms[2])});
  }
  std::string d = "## Depth-image sampling: conventional, depth peeling, NRR (thesis ch. 2)\n\n";
  d += "Three depth images of each scene (256², " + fixed(p.m("demo_sampling_nest_frames"), 0) +
       " output frames along the view set); the reference is the "
       "scene itself: \"available\" is the share of each output frame's visible samples that the images hold "
       "(100 % = nothing missing). Time of the three images; the issue's bounds are NRR ≤ 2.5× conventional "
       "and ≤ 1.3× 3-layer peeling.\n\n";
  d += markdown({"scene", "available % avg, conventional / NRR / peeling", "thesis Table 4",
                 "ms conventional / NRR / peeling", "NRR ÷ conventional", "NRR ÷ peeling"},
                rows);
  d += "\n" + p.commands({"demo-sampling"});
  return {{"Depth-image sampling (NRR)", "nest, grass, city, tree; 256²",
           "NRR images hold " + span(nrr_avail, 1) + " % of the output samples (conventional " +
               span(conv_avail, 1) + " %)",
           "NRR 59–98 % (conventional 55–97 %)", "NRR takes " + span(nrr_over_conv, 2) + "× conventional's time",
           "— (issue bound ≤ 2.5×)"},
          d};
}

Part shadows_part(Page& p) {
  std::vector<Row> rows;
  const double geometry_ms = p.m("shadows_geometry_time_shadow_ms");
  const double rays_ms = p.m("shadows_time_rays_ms");
  double nrr_error = 0.0, nrr_speed = 0.0;
  for (int k = 0; k < 3; ++k) {
    const std::string s = std::string("shadows_") + kShadowMethods[k] + "_";
    const double total =
        p.m(s + "time_reference_ms") + p.m(s + "time_reconstruct_ms") + p.m(s + "time_shadow_ms");
    const double vis = p.m(s + "visibility_error_mean");
    if (k == 0) nrr_error = vis, nrr_speed = geometry_ms / total;
    rows.push_back({kShadowMethods[k], fixed(p.m(s + "intensity_error_mean"), 2) + " · " + fixed(vis, 2),
                    kShadowThesis[k], fixed(p.m(s + "visibility_error_rays_mean"), 2), fixed(total, 0),
                    times(geometry_ms / total)});
  }
  std::vector<Row> sweep;
  for (const char* size : {"0.50", "1", "2"}) {
    Row r{size};
    for (const char* method : kShadowMethods)
      r.push_back(fixed(p.m(std::string("demo_shadows_city_light_") + size + "_" + method + "_visibility_error_mean"), 2));
    sweep.push_back(r);
  }
  std::string d = "## Soft shadows from reconstructed depth images (thesis ch. 3)\n\n";
  const double n = std::sqrt(p.m("shadows_light_samples"));
  d += "city, light size " + fixed(p.m("shadows_light_size"), 1) + " (× scene diagonal), " + fixed(n, 0) + "×" +
       fixed(n, 0) + " light samples, reference images 512², output 256². Errors "
       "(0–255) against the thesis' ground truth, shadow maps of the original geometry (that took " +
       fixed(geometry_ms, 0) + " ms), and against exact Embree shadow rays (" + fixed(rays_ms, 0) +
       " ms). Time = reference images + reconstruction + soft shadows; speed = the geometry's shadow-map "
       "time ÷ that.\n\n";
  d += markdown({"sampling", "intensity · visibility error", "thesis Table 9 (1024²)", "visibility error vs rays",
                 "ms", "speed vs geometry"},
                rows);
  d += "\nMean visibility error vs light size (demo, same setting):\n\n";
  d += markdown({"light size", "NRR", "conventional", "peeling"}, sweep);
  d += "\n" + p.commands({"shadows", "demo-shadows"});
  return {{"Soft shadows (NRR reconstruction)", "city, light 1, 8×8 samples, 512² → 256²",
           "mean visibility error " + fixed(nrr_error, 2) + " vs geometry shadow maps", "2.07 (city, 1024²)",
           times(nrr_speed) + " geometry shadow maps",
           "slower than the geometry below ≈ 2.5M triangles (Fig. 20); city has 49k"},
          d};
}

Part envmap_part(Page& p) {
  std::vector<Row> rows;
  std::vector<double> rect_mae, rect_speed;
  // Wang et al. 2012, Table 1: rectified and plain fps, ray tracing < 1 fps.
  const char* const paper[] = {"112 fps (plain 151; ray traced < 1)", "71 fps (plain 100; ray traced < 1)", "—"};
  for (size_t i = 0; i < 3; ++i) {
    const std::string s = std::string("demo_envmap_") + kEnvmapScenes[i] + "_";
    const double ref_ms = p.m(s + "reference_ms");
    for (const char* method : kEnvmapMethods) {
      const double mae = p.m(s + method + "_mae"), ms = p.m(s + method + "_ms");
      if (std::string(method) == "rectified") rect_mae.push_back(mae), rect_speed.push_back(ref_ms / ms);
      rows.push_back({kEnvmapScenes[i], method, fixed(mae, 2), fixed(ms, 1), fixed(ref_ms, 1), times(ref_ms / ms),
                      std::string(method) == "rectified" ? paper[i] : ""});
    }
  }
  std::string d = "## Environment maps with distance and position rectification (Wang et al. 2012)\n\n";
  d += "512×384, 256² cube faces, median of 3 frames per method, round-robin; MAE over the reflector against "
       "Embree tracing the same mirror rays. Per frame, the cube map's build excluded (it is built once).\n\n";
  d += markdown({"scene", "method", "MAE", "ms/frame", "Embree ms", "speed vs Embree", "paper, Table 1 (GPU)"}, rows);
  const auto rect_over_plain = [&](const char* scene) {
    const std::string s = std::string("demo_envmap_") + scene + "_";
    return times(p.m(s + "rectified_ms") / p.m(s + "envmap_ms"));
  };
  d += "\nRectified ÷ plain time per frame: room-reflector " + rect_over_plain("room-reflector") +
       " (paper 1.35×), room-car " + rect_over_plain("room-car") + " (paper 1.41×).\n";
  d += "\n" + p.commands({"demo-envmap"});
  return {{"Environment maps (rectified)", "room-reflector, room-car, room-parallax; 512×384",
           "MAE " + span(rect_mae, 2) + " (plain env map: see below)", "— (no error figure)",
           span(rect_speed, 1) + "× Embree", "> 112× and > 71× (112, 71 fps vs < 1 fps ray traced)"},
          d};
}

Part cluster_part(Page& p) {
  std::vector<Row> rows;
  std::vector<double> mae, speed;
  const char* const thesis_occlusion[] = {"0.62 / 1.3", "2.75 / 3.5"};
  const char* const thesis_speed[] = {"15–16× (18 / 15 vs 1.1 / 1.0 fps)", "5–8× (17 / 18 vs 3.3 / 2.3 fps)"};
  for (size_t i = 0; i < 2; ++i) {
    const std::string s = std::string("demo_cluster_") + kReflectPaths[i] + "_";
    const double r = p.m(s + "cluster_mae_r"), g = p.m(s + "cluster_mae_g"), b = p.m(s + "cluster_mae_b");
    mae.push_back(r), mae.push_back(g), mae.push_back(b);
    speed.push_back(p.m(s + "speedup_static"));
    rows.push_back({kReflectPathNames[i], fixed(r, 2) + " / " + fixed(g, 2) + " / " + fixed(b, 2),
                    fixed(p.m(s + "occlusion_error_pct_avg"), 2) + " / " + fixed(p.m(s + "occlusion_error_pct_max"), 2),
                    thesis_occlusion[i], fixed(p.m(s + "cluster_ms_avg"), 0), fixed(p.m(s + "reference_ms_avg"), 0),
                    times(speed.back()), thesis_speed[i]});
  }
  std::string d = "## Cluster depth-image reflections (thesis ch. 4)\n\n";
  d += "256², 2×2 samples per pixel, 8 lobe rays on glossy surfaces, " +
       fixed(p.m("demo_cluster_living-room_walk_frames"), 0) + " frames per path; Embree traces the "
       "identical rays with identical shading. Thesis MAE per channel r / g / b: 6 / 3 / 9 (§4.7.1); its "
       "speed is the GPU method against OptiX (Table 13).\n\n";
  d += markdown({"scene / path", "MAE r / g / b", "occlusion errors % avg / max", "thesis", "ms/frame", "Embree ms",
                 "speed vs Embree", "thesis speed"},
                rows);
  d += "\n" + p.commands({"demo-cluster"});
  return {{"Cluster depth-image reflections", "living-room, bathroom walks; 256², 3 frames",
           "MAE " + span(mae, 2) + " per channel", "6 / 3 / 9 per channel", span(speed, 2) + "× Embree",
           "5–16× OptiX (GPU)"},
          d};
}

Part temporal_part(Page& p) {
  std::vector<Row> rows;
  std::vector<double> mae, speed;
  const char* const thesis_speed[] = {"3.6–3.7×", "1.8–1.9×"};
  for (size_t i = 0; i < 2; ++i) {
    const std::string s = std::string("demo_temporal_") + kReflectPaths[i] + "_";
    mae.push_back(p.m(s + "temporal_mae_avg"));
    speed.push_back(p.m(s + "speedup_vs_reference"));
    rows.push_back({kReflectPathNames[i], fixed(mae.back(), 2), fixed(p.m(s + "direct_mae_avg"), 2),
                    fixed(p.m(s + "recompute_pct_avg"), 1), fixed(p.m(s + "keyframe_interval_avg"), 1),
                    times(speed.back()), times(p.m(s + "frame_speedup_vs_reference")), thesis_speed[i]});
  }
  std::string d = "## Temporal reuse of reflections (thesis ch. 5)\n\n";
  d += fixed(p.m("demo_temporal_living-room_walk_width"), 0) + "², the first " +
       fixed(p.m("demo_temporal_living-room_walk_frames"), 0) +
       " frames of each walk, 8 lobe rays on glossy surfaces; against full ray tracing of "
       "every frame. Thesis (500 frames at 1024², GPU): MAE 0.13–0.45, 18–21 % recomputed. Speed of the "
       "reflections alone and of the whole frame (diffuse shading included).\n\n";
  d += markdown({"scene / path", "MAE", "direct reprojection MAE", "recomputed %", "key-frame interval",
                 "speed (reflections)", "speed (frame)", "thesis, Table 22"},
                rows);
  d += "\n" + p.commands({"demo-temporal"});
  return {{"Temporal reuse of reflections", "living-room, bathroom walks; 128², 60 frames",
           "MAE " + span(mae, 2), "0.13–0.45", span(speed, 2) + "× Embree (reflections)",
           "1.8–3.7× (Table 22)"},
          d};
}

Part visibility_part(Page& p) {
  std::vector<Row> rows;
  std::vector<double> agree, ties, map_ms;
  for (size_t i = 0; i < 6; ++i) {
    const std::string s = std::string("demo_visibility_") + kVisibilityModels[i] + "_";
    agree.push_back(p.m(s + "agreement_pct_worst"));
    ties.push_back(p.m(s + "agreement_with_ties_pct_worst"));
    map_ms.push_back(p.m(s + "map_ms_avg"));
    rows.push_back({kVisibilityModels[i], fixed(p.m(s + "polygons"), 0), kVisibilityPaperPolygons[i],
                    fixed(p.m(s + "agreement_pct"), 3), fixed(agree.back(), 3),
                    fixed(ties.back(), 3), fixed(p.m(s + "build_ms"), 1),
                    fixed(map_ms.back(), 2) + " / " + fixed(p.m(s + "map_ms_max"), 2),
                    fixed(p.m(s + "maps_failed_selfcheck"), 0)});
  }
  std::vector<Row> floors;
  for (const char* n : {"1", "2", "3"})
    floors.push_back({n, fixed(p.m(std::string("demo_visibility_building") + n + "_polygons"), 0),
                      fixed(p.m(std::string("demo_visibility_building") + n + "_map_ms_avg"), 2)});
  std::string d = "## Exact visibility maps (Funkhouser)\n\n";
  d += "256² maps, the first " + fixed(p.m("demo_visibility_rooms_viewpoints"), 0) +
       " frames of each model's walk; the map's polygon at every pixel center against "
       "Embree's item buffer (worst = the worst frame; ties = coplanar polygons). Embree's item buffer is the "
       "check, not timed. The paper (195 MHz R10000) reports maps in a little over 1 s at most.\n\n";
  d += markdown({"model", "polygons", "paper polygons", "agreement %", "worst frame %", "worst with ties %",
                 "BSP build ms", "map ms avg / max", "maps failing self-check"},
                rows);
  d += "\nOutput sensitivity, building with N floors (the walk stays on floor 1):\n\n";
  d += markdown({"floors", "polygons", "map ms avg"}, floors);
  d += "\n" + p.commands({"demo-visibility"});
  return {{"Exact visibility maps", "6 models, 256², 10 frames each",
           "item buffer agreement ≥ " + fixed(lowest(agree), 2) + " % per frame (" + fixed(lowest(ties), 3) +
               " % with ties)",
           "exact (no figure)", "map " + span(map_ms, 2) + " ms avg; Embree not timed", "≈ 1 s per map (R10000)"},
          d};
}

Part gibr_part(Page& p) {
  const std::string s = "demo_gibr_rooms_";
  std::vector<Row> rows;
  for (const char* mapping : {"vismap", "itembuffer"})
    rows.push_back({std::string(mapping) == "vismap" ? "visibility map" : "item buffer",
                    fixed(p.m(s + "psnr_" + mapping), 2), fixed(p.m(s + "psnr_seen_" + mapping), 2),
                    fixed(p.m(s + "mae_" + mapping), 2),
                    fixed(p.m(s + "silhouette_mae_" + mapping), 2), fixed(p.m(s + "unseen_pct_" + mapping), 2)});
  std::string d = "## Hybrid geometry- and image-based rendering (Funkhouser)\n\n";
  d += "rooms: " + fixed(p.m(s + "photos"), 0) + " photographs at 160×120 mapped onto the polygons through "
       "each photograph's exact visibility map or through a z-buffer item buffer; 4 novel views at 320×240 "
       "against reference renders (pixels no photograph saw are holes, counted in the PSNR and MAE). The "
       "paper gives no figure: its claim is fewer wrongly colored pixels at "
       "silhouettes. A novel view takes " + fixed(p.m(s + "novel_view_ms"), 1) + " ms (" +
       fixed(p.m(s + "novel_view_fps"), 0) + " fps); the reference render is not timed.\n\n";
  d += markdown({"mapping", "PSNR dB", "PSNR dB, seen pixels", "MAE", "MAE ≤ 2 px of silhouettes", "unseen %"},
                rows);
  d += "\n" + p.commands({"demo-gibr"});
  return {{"Geometry- and image-based rendering", "rooms, 16 photographs, 4 views 320×240",
           "MAE " + fixed(p.m(s + "mae_vismap"), 2) + " (item buffer " + fixed(p.m(s + "mae_itembuffer"), 2) + ")",
           "— (no figure)", fixed(p.m(s + "novel_view_fps"), 0) + " fps; reference not timed", "—"},
          d};
}

Part viewer_part(Page& p) {
  std::vector<Row> rows;
  std::vector<double> mae;
  const double ref_ms = p.m("bench_view_reference_moving_ms");
  for (const char* t : kViewerTechniques) {
    const std::string s = std::string("bench_view_") + t + "_";
    const double ms = p.m(s + "moving_ms");
    if (std::string(t) != "reference") mae.push_back(p.m(s + "error_mae"));
    rows.push_back({t,
                    fixed(p.m(s + "render_width"), 0) + "×" + fixed(p.m(s + "render_height"), 0),
                    fixed(ms, 1), fixed(p.m(s + "moving_fps"), 1), times(ref_ms / ms), fixed(p.m(s + "error_mae"), 2)});
  }
  std::string d = "## Interactive viewer\n\n";
  d += "`proxima bench view`: the viewer's session without a window on living-room, window 640×360, "
       "rendering at half size while the camera moves (medians over blocks of moving frames, round-robin "
       "over the techniques); MAE of the still, full-size frame against the reference renderer. The issue's "
       "target: ≥ 15 frames/s for the reference while moving.\n\n";
  d += markdown({"technique", "rendered while moving", "ms/frame", "frames/s", "speed vs reference", "MAE still"},
                rows);
  d += "\n" + p.commands({"bench_view"});
  return {{"Interactive viewer", "living-room, 640×360 window, 320×180 while moving",
           "MAE " + span(mae, 2) + " (still frames)", "—", fixed(p.m("bench_view_reference_moving_fps"), 1) +
               " fps reference while moving",
           "— (target ≥ 15 fps with resolution scaling; this run renders 320×180)"},
          d};
}

// Every technique against Embree (the demo's "bench" section), when the merged results
// hold its table: the table as the demo wrote it. Empty for results made before it existed.
std::string bench_detail(const Page& p) {
  const std::string title = "demo: Techniques vs Embree at the demo's settings";
  for (const Table& t : p.results().tables)
    if (t.title.rfind(title, 0) == 0) {
      Table shown = t;
      shown.title.erase(0, std::string("demo: ").size());
      return "\n## Techniques vs Embree\n\nEach technique and Embree timed in the same run (the demo's "
             "settings; error-vs-ms plots per technique in the demo's report, `proxima bench techniques` "
             "for 5 interleaved repetitions).\n\n" +
             markdown_table(shown) + "\n" + p.commands({"demo-bench"});
    }
  return "";
}

std::string header(const Page& p) {
  const Results& r = p.results();
  std::string d = "# Measured results\n\n";
  d += "<!-- Generated: do not edit. scripts/results.sh runs the commands below and writes this page with "
       "`proxima results page docs/results.json --out docs/RESULTS.md`. -->\n\n";
  d += "Generated from [results.json](results.json) by `scripts/results.sh`; regenerating it from that file "
       "gives this page byte for byte (tested). How each figure was reached, dated: [the journal](journal/README.md); "
       "changes of behaviour or speed: [CHANGELOG.md](../CHANGELOG.md).\n\n";
  d += "- commit `" + r.commit + "`, " + r.build + " build; CPU " + r.cpu + "; " + std::to_string(r.threads) +
       " threads in every run\n";
  d += "- errors on the 0–255 display scale unless named otherwise; deterministic (the same for any thread "
       "count)\n";
  d += "- speed = the reference's time ÷ the technique's, measured in the same run on the same machine (> 1: "
       "faster than the reference); the machine is a shared 2-core VM, so times move with its load\n";
  d += "- the papers ran on GPUs (thesis) or 1990s workstations (Funkhouser): compare their ratios and errors, "
       "not their times\n\n";
  d += "Runs:\n\n" + p.commands({"demo", "bench_trace", "bench_raster", "shadows", "bench_view"});
  return d;
}

}  // namespace

ResultsPage results_page(const Results& merged) {
  Page p(merged);
  std::vector<Part> parts;
  parts.push_back(reference_part(p));
  parts.push_back(raster_part(p));
  parts.push_back(sampling_part(p));
  parts.push_back(shadows_part(p));
  parts.push_back(envmap_part(p));
  parts.push_back(cluster_part(p));
  parts.push_back(temporal_part(p));
  parts.push_back(visibility_part(p));
  parts.push_back(gibr_part(p));
  parts.push_back(viewer_part(p));
  std::vector<Row> summary;
  for (const Part& part : parts) summary.push_back(part.summary);
  std::string page = header(p);
  page += "\n## Summary\n\n";
  page += markdown({"technique", "setting", "error vs reference", "paper", "speed vs reference", "paper"}, summary);
  for (const Part& part : parts) page += "\n" + part.detail;
  page += bench_detail(p);
  page += "\nThe demo took " + fixed(p.m("demo_demo_seconds"), 0) + " s.\n";
  return {page, p.missing()};
}

}  // namespace proxima
