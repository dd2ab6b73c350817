// `proxima gibr`: the four phases of Funkhouser's hybrid geometry- and image-based rendering
// system (section 2) on a built-in model: synthetic calibrated photographs, (1) BSP →
// winged pair, (2) a visibility map per photograph, (3) radiance maps, (4) novel views
// along the walkthrough path, each compared with a reference render; visibility-map mapping
// against the item-buffer (z-buffer) mapping of Debevec et al. docs/gibr.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/gibr/novel_view.h"
#include "proxima/gibr/photo_set.h"
#include "proxima/gibr/radiance_map.h"
#include "proxima/scene/load.h"
#include "proxima/visibility/bsp_build.h"

namespace proxima::cli {

namespace {

using namespace proxima::gibr;
using namespace proxima::visibility;

struct GibrFlags {
  CommonOptions common;
  GibrModelOptions model;  // photographs, texel, period, supersample, mapping (phases 1–3)
  std::string views = "path";
  int frames = 10;
  int k = 3;
  int novel_ss = 0;         // 0 = the ground truth's (--supersample, 2×2): ≥ 13 fps on all three scenes (RESULTS)
  int hole_radius = NovelViewOptions{}.hole_radius;
  double offpath = 0.5;     // meters, --views offpath
  bool photo_images = true;
  int fps_repeat = 3;
};

// Pooled error over frames: squared and absolute sums on the 0–255 display scale.
struct Pool {
  double se = 0.0, ae = 0.0, values = 0.0, pixels = 0.0;
  void add(const ImageError& e) {
    if (e.pixels == 0) return;
    const double n = 3.0 * double(e.pixels);
    const double mse = std::isfinite(e.psnr_db) ? 255.0 * 255.0 / std::pow(10.0, e.psnr_db / 10.0) : 0.0;
    se += mse * n;
    ae += e.mae_avg * n;
    values += n;
    pixels += double(e.pixels);
  }
  double psnr() const { return values > 0 && se > 0 ? 10.0 * std::log10(255.0 * 255.0 / (se / values)) : INFINITY; }
  double mae() const { return values > 0 ? ae / values : 0.0; }
};

std::string numbered(const char* stem, int i, const char* suffix) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%03d%s", stem, i, suffix);
  return buf;
}

}  // namespace

Command register_gibr(CLI::App& root) {
  static GibrFlags f;
  auto* app = root.add_subcommand(
      "gibr", "hybrid geometry- and image-based rendering: photos → visibility maps → radiance maps → novel views");
  add_scene_flag(app, f.common, "rooms");
  f.common.width = 640;
  f.common.height = 480;
  add_size_flags(app, f.common);
  add_threads_flag(app, f.common);
  add_seed_flag(app, f.common);
  add_out_flag(app, f.common, true);
  app->add_option("--photos", f.model.photos, "calibrated photographs rendered along the walk path")->capture_default_str();
  app->add_option("--views", f.views,
                  "novel views: 'path' (along the walk path), 'offpath' (the path's cameras moved sideways by "
                  "--offpath) or 'photos' (at the first photo poses)")
      ->capture_default_str();
  app->add_option("--frames", f.frames, "novel views rendered and compared")->capture_default_str();
  app->add_option("--photo-width", f.model.photo_width, "photograph width in pixels")->capture_default_str();
  app->add_option("--photo-height", f.model.photo_height, "photograph height in pixels")->capture_default_str();
  app->add_option("--camera-file", f.model.camera_file,
                  "photographs from this camera file (JSON, docs/gibr.md; e.g. a run's photos/cameras.json or real "
                  "photographs of the model) instead of rendering --photos of them");
  app->add_option("--texel", f.model.texel, "radiance-map texel size in meters (default: per scene, docs/gibr.md)");
  app->add_option("--period", f.model.period, "texture repeat in meters (default: per scene)");
  app->add_option("--k", f.k, "photographs blended per pixel")->capture_default_str();
  app->add_option("--novel-ss", f.novel_ss,
                  "s×s samples per novel-view pixel, both mappings (0 = the ground truth's --supersample)")
      ->capture_default_str();
  app->add_option("--hole-radius", f.hole_radius,
                  "texels searched around a novel-view hole for the nearest sample, both mappings (0 = no fill)")
      ->capture_default_str();
  app->add_option("--offpath", f.offpath, "meters the 'offpath' views are moved off the walk path")
      ->capture_default_str();
  app->add_option("--supersample", f.model.supersample, "k×k samples per photograph / ground-truth pixel")
      ->capture_default_str();
  app->add_flag("--exclude-boundaries", f.model.exclude_boundaries,
                "visibility-map mapping also drops pixels touching any edge between different polygons");
  app->add_flag("--whole-pixels", f.model.whole_pixels,
                "visibility-map mapping without exact-visible texels: texels seen only in pixels not mapped onto "
                "their polygon (silhouettes, creases) get no sample");
  app->add_flag("!--no-unmix", f.model.unmix,
                "visibility-map mapping without unmixing silhouette pixels: exact-visible texels take colors only "
                "from pixels wholly on their polygon");
  app->add_option("--fps-repeat", f.fps_repeat, "timed renders of each novel view (median → novel_view_fps)")
      ->capture_default_str();
  app->add_flag("!--no-photo-images", f.photo_images, "do not write the photographs as PNG");

  return {app, [] {
            if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
            if (f.frames < 1 || f.frames > 10000) fail_input("--frames: must be in 1..10000");
            if (f.views != "path" && f.views != "photos" && f.views != "offpath")
              fail_input("--views: must be 'path', 'offpath' or 'photos' (got '" + f.views + "')");
            if (f.novel_ss < 0 || f.novel_ss > 8) fail_input("--novel-ss: must be in 0..8");
            if (f.hole_radius < 0 || f.hole_radius > 4096) fail_input("--hole-radius: must be in 0..4096");
            if (!(f.offpath >= 0.0 && f.offpath <= 1e3)) fail_input("--offpath: must be a distance in meters ≥ 0");
            if (f.fps_repeat < 1 || f.fps_repeat > 1000) fail_input("--fps-repeat: must be in 1..1000");
            if (f.k < 1 || f.k > 64) fail_input("--k: must be in 1..64");
            ThreadLimit limit(f.common.threads);
            const Scene model_scene = load_scene(f.common.scene);
            validate_camera(look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60, f.common.width, f.common.height), "--width/--height");
            // Phases 1–3 with both mappings; it checks the photograph flags before any work.
            f.model.item_buffer = true;
            f.model.seed = f.common.seed;
            const GibrModel g = build_gibr_model(model_scene, f.model);
            for (const std::string& failure : g.stats.selfcheck_failures)
              std::fprintf(stderr, "warning: %s: visibility map of %s (failed its self-check)\n", model_scene.name.c_str(),
                           failure.c_str());
            const CameraPath& path = model_scene.camera_paths.front();
            const Scene& scene = g.scene;
            const ModelPolygons& model = g.model;
            const RayScene& rays = *g.rays;
            const std::vector<Camera>& cams = g.cameras;
            const RadianceMaps& vis_maps = g.maps;
            const RadianceMaps& item_maps = g.item_maps;
            const double texel = g.texel, far = g.far;

            Results results;
            results.command = command_line();
            results.threads = active_threads();
            auto& m = results.metrics;
            Table phases{"time per phase (" + model_scene.name + ")", {"phase", "ms"}, {}};
            phases.rows.push_back({std::string("photographs (reference renders)"), g.stats.photos_ms});
            auto out = prepare_out_dir(f.common.out);
            std::vector<CalibratedPhoto> calibrated;
            std::filesystem::create_directories(out / "photos");
            for (size_t i = 0; i < cams.size(); ++i) {
              calibrated.push_back({numbered("photo", int(i), ".png"), cams[i]});
              if (f.photo_images) write_png_linear(out / "photos" / calibrated.back().image, g.photos[i]);
            }
            write_camera_file(out / "photos" / "cameras.json", calibrated);
            phases.rows.push_back({std::string("1 spatial subdivision (BSP → winged pair)"), g.stats.bsp.build_ms});
            phases.rows.push_back({std::string("2 visibility maps (all photographs)"), g.stats.vismap_ms});
            phases.rows.push_back({std::string("2' item buffers (baseline, all photographs)"), g.stats.itembuffer_ms});
            phases.rows.push_back({std::string("3 radiance maps (visibility-map mapping)"), vis_maps.stats.ms});
            phases.rows.push_back({std::string("3' radiance maps (item-buffer mapping)"), item_maps.stats.ms});
            Table stats{"radiance maps of " + model_scene.name + " (texel " + std::to_string(texel) + " m)",
                        {"mapping", "photos", "layers", "samples", "texels", "texels covered %", "pixels mapped", "MiB"},
                        {}};
            for (const auto& [name, maps] : {std::pair<const char*, const RadianceMaps*>{"visibility map", &vis_maps},
                                              std::pair<const char*, const RadianceMaps*>{"item buffer", &item_maps}}) {
              const RadianceStats& s = maps->stats;
              stats.rows.push_back({std::string(name), double(s.photos), double(s.layers), double(s.samples), double(s.texels),
                                    100.0 * double(s.texels_covered) / double(std::max<size_t>(1, s.texels)),
                                    double(s.pixels_mapped), double(s.bytes) / (1024.0 * 1024.0)});
            }
            m["texel_m"] = texel;
            m["photos"] = double(cams.size());
            m["layers_vismap"] = double(vis_maps.stats.layers);
            m["samples_vismap"] = double(vis_maps.stats.samples);
            m["samples_unmixed_vismap"] = double(vis_maps.stats.samples_unmixed);
            m["samples_extrapolated_vismap"] = double(vis_maps.stats.samples_extrapolated);
            m["samples_itembuffer"] = double(item_maps.stats.samples);
            m["texels_covered_pct_vismap"] = 100.0 * double(vis_maps.stats.texels_covered) / double(std::max<size_t>(1, vis_maps.stats.texels));
            m["pixels_mapped_vismap"] = double(vis_maps.stats.pixels_mapped);
            m["pixels_mapped_itembuffer"] = double(item_maps.stats.pixels_mapped);

            // Phase 4: novel views, ground truth and errors.
            std::vector<Camera> views;
            if (f.views == "offpath")
              views = offpath_poses(rays, path, f.frames, f.common.width, f.common.height, f.offpath, 0.01f, far);
            for (int i = 0; f.views != "offpath" && i < f.frames; ++i) {
              if (f.views == "photos") {
                views.push_back(cams[size_t(i) % cams.size()]);
              } else {
                const float t = f.frames == 1 ? path.keys.front().time
                                              : path.keys.front().time + (path.keys.back().time - path.keys.front().time) *
                                                                             float(i) / float(f.frames - 1);
                views.push_back(camera_at_time(path, t, f.common.width, f.common.height, 0.01f, far));
              }
            }
            std::filesystem::create_directories(out / "views");
            NovelViewOptions nvo;
            nvo.k = f.k;
            nvo.hole_radius = f.hole_radius;
            // Both mappings through the same renderer, antialiased like the ground truth.
            nvo.supersample = f.novel_ss > 0 ? f.novel_ss : f.model.supersample;
            NovelViewOptions nvo1 = nvo;  // one sample per pixel: its cost, for comparison
            nvo1.supersample = 1;
            std::vector<double> frame_ms_1spp;
            NovelViewScratch scratch, scratch1;  // raster buffers kept between frames, as a viewer would
            Stopwatch w;
            Pool all_v, all_i, sil_v, sil_i, seen_v, seen_i, silseen_v, silseen_i;
            // Error by region: which mapping saw the pixel's surface (2 bits: vis-map hole,
            // item-buffer hole) × all pixels / within 2 px of silhouettes; [mapping].
            Pool region[4][2][2];
            double region_total = 0.0;
            std::vector<double> frame_ms, frame_cpu_ms;
            double truth_ms = 0.0, holes_v = 0.0, holes_i = 0.0, covered = 0.0;
            Table per_view{"novel views of " + model_scene.name + " ('" + f.views + "')",
                           {"view", "psnr vismap", "psnr itembuffer", "mae vismap", "mae itembuffer", "sil mae vismap",
                            "sil mae itembuffer", "unseen % vismap", "ms vismap"},
                           {}};
            for (size_t i = 0; i < views.size(); ++i) {
              const Camera& cam = views[i];
              NovelView nv;
              // Timing: --fps-repeat renders of the same view, wall and process CPU time each.
              for (int r = 0; r < f.fps_repeat; ++r) {
                const std::clock_t c0 = std::clock();
                nv = render_novel_view(scene, model, vis_maps, cam, nvo, &scratch);
                frame_cpu_ms.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
                frame_ms.push_back(nv.raster_ms + nv.blend_ms);
                if (nvo.supersample > 1) {
                  const NovelView n1 = render_novel_view(scene, model, vis_maps, cam, nvo1, &scratch1);
                  frame_ms_1spp.push_back(n1.raster_ms + n1.blend_ms);
                }
              }
              const NovelView ni = render_novel_view(scene, model, item_maps, cam, nvo, &scratch);
              w.restart();
              const ImageF truth = render_photo(scene, rays, cam, f.model.supersample, derive_seed(f.common.seed, i, 2));
              truth_ms += w.elapsed_ms();
              const ImageU8 sil = silhouette_pixel_mask(trace_visibility_map(g.winged_pair, cam), 2.0);
              ImageU8 seen(cam.width, cam.height, 1, 0);
              for (int y = 0; y < cam.height; ++y)
                for (int x = 0; x < cam.width; ++x) seen.at(x, y) = !nv.unseen.at(x, y) && !ni.unseen.at(x, y);
              const ImageError ev = compare_images(nv.color, truth), ei = compare_images(ni.color, truth);
              const ImageError sv = compare_images(nv.color, truth, &sil), si = compare_images(ni.color, truth, &sil);
              all_v.add(ev);
              all_i.add(ei);
              sil_v.add(sv);
              sil_i.add(si);
              seen_v.add(compare_images(nv.color, truth, &seen));
              seen_i.add(compare_images(ni.color, truth, &seen));
              ImageU8 sil_seen = sil;
              for (size_t p = 0; p < sil_seen.data().size(); ++p) sil_seen.data()[p] = sil.data()[p] && seen.data()[p];
              silseen_v.add(compare_images(nv.color, truth, &sil_seen));
              silseen_i.add(compare_images(ni.color, truth, &sil_seen));
              for (int rgn = 0; rgn < 4; ++rgn)
                for (int band = 0; band < 2; ++band) {
                  ImageU8 mask(cam.width, cam.height, 1, 0);
                  for (int y = 0; y < cam.height; ++y)
                    for (int x = 0; x < cam.width; ++x)
                      mask.at(x, y) = (nv.unseen.at(x, y) ? 2 : 0) + (ni.unseen.at(x, y) ? 1 : 0) == rgn &&
                                      (band == 0 || sil.at(x, y));
                  region[rgn][band][0].add(compare_images(nv.color, truth, &mask));
                  region[rgn][band][1].add(compare_images(ni.color, truth, &mask));
                }
              region_total += double(cam.width) * double(cam.height);
              holes_v += double(nv.holes);
              holes_i += double(ni.holes);
              covered += double(nv.covered);
              per_view.rows.push_back({double(i), ev.psnr_db, ei.psnr_db, ev.mae_avg, ei.mae_avg, sv.mae_avg, si.mae_avg,
                                       100.0 * double(nv.holes) / double(std::max<size_t>(1, nv.covered)),
                                       nv.raster_ms + nv.blend_ms});
              write_png_linear(out / "views" / numbered("vismap", int(i), ".png"), nv.color);
              write_png_linear(out / "views" / numbered("itembuffer", int(i), ".png"), ni.color);
              write_png_linear(out / "views" / numbered("truth", int(i), ".png"), truth);
              write_png_linear(out / "views" / numbered("error_vismap", int(i), ".png"),
                               error_heatmap(error_image(nv.color, truth), 32.0f));
              write_png_linear(out / "views" / numbered("error_itembuffer", int(i), ".png"),
                               error_heatmap(error_image(ni.color, truth), 32.0f));
              ImageU8 unseen_png(cam.width, cam.height, 1, 0);
              for (size_t p = 0; p < unseen_png.data().size(); ++p) unseen_png.data()[p] = nv.unseen.data()[p] ? 255 : 0;
              write_png(out / "views" / numbered("unseen_vismap", int(i), ".png"), unseen_png);
              if (i == 0)
                results.images = {{"novel_vismap", "views/vismap_000.png"}, {"novel_itembuffer", "views/itembuffer_000.png"},
                                  {"truth", "views/truth_000.png"}, {"error_vismap", "views/error_vismap_000.png"},
                                  {"error_itembuffer", "views/error_itembuffer_000.png"}};
            }
            const double med = median(frame_ms);
            m["novel_view_cpu_ms"] = median(frame_cpu_ms);
            phases.rows.push_back({std::string("4 novel view (median per frame, visibility-map maps)"), med});
            phases.rows.push_back({std::string("4 novel view, process CPU time (median per frame, all threads)"), m["novel_view_cpu_ms"]});
            phases.rows.push_back({std::string("ground truth (reference renders, all views)"), truth_ms});
            m["psnr_vismap"] = all_v.psnr();
            m["psnr_itembuffer"] = all_i.psnr();
            m["mae_vismap"] = all_v.mae();
            m["mae_itembuffer"] = all_i.mae();
            m["silhouette_mae_vismap"] = sil_v.mae();
            m["silhouette_mae_itembuffer"] = sil_i.mae();
            m["silhouette_psnr_vismap"] = sil_v.psnr();
            m["silhouette_psnr_itembuffer"] = sil_i.psnr();
            m["silhouette_mae_seen_vismap"] = silseen_v.mae();
            m["silhouette_mae_seen_itembuffer"] = silseen_i.mae();
            m["psnr_seen_vismap"] = seen_v.psnr();
            m["psnr_seen_itembuffer"] = seen_i.psnr();
            m["unseen_pct_vismap"] = 100.0 * holes_v / std::max(1.0, covered);
            m["unseen_pct_itembuffer"] = 100.0 * holes_i / std::max(1.0, covered);
            m["novel_view_ms"] = med;
            m["novel_view_fps"] = med > 0 ? 1000.0 / med : 0.0;
            m["novel_view_ss"] = double(nvo.supersample);
            if (!frame_ms_1spp.empty()) {
              const double med1 = median(frame_ms_1spp);
              m["novel_view_ms_1spp"] = med1;
              m["novel_view_fps_1spp"] = med1 > 0 ? 1000.0 / med1 : 0.0;
              phases.rows.push_back({std::string("4 novel view at 1 sample per pixel (median per frame, for comparison)"), med1});
            }
            m["bsp_ms"] = g.stats.bsp.build_ms;
            m["vismap_ms_avg"] = g.stats.vismap_ms / double(cams.size());
            m["silhouette_edges_avg"] = g.stats.silhouette_edges_avg;
            m["maps_failed_selfcheck"] = double(g.stats.maps_failed_selfcheck);
            m["selfcheck_ms_avg"] = g.stats.selfcheck_ms / double(cams.size());
            Table summary{"novel views vs ground truth (" + model_scene.name + ", " + std::to_string(views.size()) +
                              " views, " + std::to_string(cams.size()) + " photos)",
                          {"mapping", "PSNR dB", "MAE", "PSNR ≤2px silhouettes", "MAE ≤2px silhouettes", "PSNR seen",
                           "MAE ≤2px silhouettes, seen", "unseen %"},
                          {{std::string("visibility map"), m["psnr_vismap"], m["mae_vismap"], m["silhouette_psnr_vismap"],
                            m["silhouette_mae_vismap"], m["psnr_seen_vismap"], m["silhouette_mae_seen_vismap"],
                            m["unseen_pct_vismap"]},
                           {std::string("item buffer"), m["psnr_itembuffer"], m["mae_itembuffer"],
                            m["silhouette_psnr_itembuffer"], m["silhouette_mae_itembuffer"], m["psnr_seen_itembuffer"],
                            m["silhouette_mae_seen_itembuffer"], m["unseen_pct_itembuffer"]}}};
            Table regions{"error by region (" + model_scene.name + ", pooled over views; % of all pixels)",
                          {"region", "pixels %", "MAE vismap", "MAE itembuffer", "≤2px sil. pixels %",
                           "≤2px sil. MAE vismap", "≤2px sil. MAE itembuffer"},
                          {}};
            const char* region_names[4] = {"both mappings saw", "vis-map saw, item-buffer hole",
                                           "item-buffer saw, vis-map hole", "both holes"};
            for (int rgn = 0; rgn < 4; ++rgn) {
              const auto& r = region[rgn];
              regions.rows.push_back({std::string(region_names[rgn]), 100.0 * r[0][0].pixels / std::max(1.0, region_total),
                                      r[0][0].mae(), r[0][1].mae(), 100.0 * r[1][0].pixels / std::max(1.0, region_total),
                                      r[1][0].mae(), r[1][1].mae()});
            }
            results.tables = {summary, regions, stats, phases, per_view};
            publish_results(out, results);
            return 0;
          }};
}

}  // namespace proxima::cli
