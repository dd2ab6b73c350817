#include "proxima/study/gibr.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/gibr/photo_set.h"
#include "proxima/gibr/radiance_map.h"
#include "proxima/gibr/silhouette_band.h"
#include "proxima/scene/camera_path.h"

namespace proxima::study {

namespace {

using namespace proxima::gibr;
using namespace proxima::visibility;

constexpr GibrViews kAllViews[] = {GibrViews::Path, GibrViews::Offpath, GibrViews::Photos};

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

std::string numbered(const char* stem, size_t i, const char* suffix) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%03zu%s", stem, i, suffix);
  return buf;
}

// The photographs (photo_images) and their camera file, into out/photos.
void write_photos(const StudyOutput& out, const GibrModel& g, bool photo_images) {
  if (!out.writes()) return;
  std::vector<CalibratedPhoto> calibrated;
  std::filesystem::create_directories(out.dir / "photos");
  for (size_t i = 0; i < g.cameras.size(); ++i) {
    // Photographs taken through a lens are kept as taken (equalized): their camera keeps the lens.
    const Lens lens = i < g.lenses.size() ? g.lenses[i] : Lens{};
    calibrated.push_back({numbered("photo", i, ".png"), g.cameras[i], lens.k1, lens.k2});
    if (photo_images) write_png_linear(out.dir / "photos" / calibrated.back().image, g.photos[i]);
  }
  write_camera_file(out.dir / "photos" / "cameras.json", calibrated);
}

// Phases 1–3: the time-per-phase rows so far, the radiance-map table and metrics.
Table add_model_results(Results& results, const std::string& name, const GibrModel& g, Table& phases) {
  phases.rows.push_back({std::string("1 spatial subdivision (BSP → winged pair)"), g.stats.bsp.build_ms});
  phases.rows.push_back({std::string("2 visibility maps (all photographs)"), g.stats.vismap_ms});
  phases.rows.push_back({std::string("2' item buffers (baseline, all photographs)"), g.stats.itembuffer_ms});
  phases.rows.push_back({std::string("3 radiance maps (visibility-map mapping)"), g.maps.stats.ms});
  phases.rows.push_back({std::string("3' radiance maps (item-buffer mapping)"), g.item_maps.stats.ms});
  Table stats{"radiance maps of " + name + " (texel " + std::to_string(g.texel) + " m)",
              {"mapping", "photos", "layers", "samples", "texels", "texels covered %", "pixels mapped", "MiB"},
              {}};
  for (const auto& [mapping, maps] : {std::pair<const char*, const RadianceMaps*>{"visibility map", &g.maps},
                                      std::pair<const char*, const RadianceMaps*>{"item buffer", &g.item_maps}}) {
    const RadianceStats& s = maps->stats;
    stats.rows.push_back({std::string(mapping), double(s.photos), double(s.layers), double(s.samples), double(s.texels),
                          100.0 * double(s.texels_covered) / double(std::max<size_t>(1, s.texels)),
                          double(s.pixels_mapped), double(s.bytes) / (1024.0 * 1024.0)});
  }
  const RadianceStats& v = g.maps.stats;
  auto& m = results.metrics;
  m["texel_m"] = g.texel;
  m["photos"] = double(g.cameras.size());
  m["layers_vismap"] = double(v.layers);
  m["samples_vismap"] = double(v.samples);
  m["samples_unmixed_vismap"] = double(v.samples_unmixed);
  m["samples_extrapolated_vismap"] = double(v.samples_extrapolated);
  m["samples_itembuffer"] = double(g.item_maps.stats.samples);
  m["texels_covered_pct_vismap"] = 100.0 * double(v.texels_covered) / double(std::max<size_t>(1, v.texels));
  m["pixels_mapped_vismap"] = double(v.pixels_mapped);
  m["pixels_mapped_itembuffer"] = double(g.item_maps.stats.pixels_mapped);
  return stats;
}

std::vector<Camera> novel_cameras(const GibrModel& g, const CameraPath& path, const GibrOptions& o) {
  if (o.views == GibrViews::Offpath)
    return offpath_poses(*g.rays, path, o.frames, o.width, o.height, o.offpath, 0.01f, float(g.far));
  std::vector<Camera> views;
  for (int i = 0; i < o.frames; ++i) {
    if (o.views == GibrViews::Photos) {
      views.push_back(g.cameras[size_t(i) % g.cameras.size()]);
    } else {
      const float t0 = path.keys.front().time, t1 = path.keys.back().time;
      const float t = o.frames == 1 ? t0 : t0 + (t1 - t0) * float(i) / float(o.frames - 1);
      views.push_back(camera_at_time(path, t, o.width, o.height, 0.01f, float(g.far)));
    }
  }
  return views;
}

// Wall times of the novel views (medians → fps) and of the ground truths.
struct Timings {
  std::vector<double> frame_ms, frame_cpu_ms, frame_ms_1spp;
  double truth_ms = 0.0;
};

// The two renderer settings (antialiased like the ground truth; one sample per pixel, for
// its cost) and their raster buffers, kept between frames as a viewer would.
struct Renderer {
  NovelViewOptions nvo, nvo1;
  NovelViewScratch scratch, scratch1;
};

// The visibility-map view rendered `repeat` times (each timed), then the item buffer's.
std::pair<NovelView, NovelView> render_views(const GibrModel& g, const Camera& cam, int repeat, Renderer& r,
                                             Timings& t) {
  NovelView nv;
  for (int k = 0; k < repeat; ++k) {
    const std::clock_t c0 = std::clock();
    nv = render_novel_view(g.scene, g.model, g.maps, cam, r.nvo, &r.scratch);
    t.frame_cpu_ms.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
    t.frame_ms.push_back(nv.raster_ms + nv.blend_ms);
    if (r.nvo.supersample > 1) {
      const NovelView n1 = render_novel_view(g.scene, g.model, g.maps, cam, r.nvo1, &r.scratch1);
      t.frame_ms_1spp.push_back(n1.raster_ms + n1.blend_ms);
    }
  }
  NovelView ni = render_novel_view(g.scene, g.model, g.item_maps, cam, r.nvo, &r.scratch);
  return {std::move(nv), std::move(ni)};
}

ImageU8 masked(const ImageU8& a, const ImageU8& b) {
  ImageU8 out = a;
  for (size_t p = 0; p < out.data().size(); ++p) out.data()[p] = a.data()[p] && b.data()[p];
  return out;
}

// Errors pooled over the views, per mapping (v = visibility map, i = item buffer).
struct Errors {
  Pool all_v, all_i, sil_v, sil_i, seen_v, seen_i, silseen_v, silseen_i;
  // Within 2 px of the view's or a photograph's silhouettes (reprojected_band).
  Pool band_v, band_i;
  // By region: which mapping saw the pixel's surface (2 bits: vis-map hole, item-buffer
  // hole) × all pixels / within 2 px of silhouettes; [mapping].
  Pool region[4][2][2];
  double region_total = 0.0, holes_v = 0.0, holes_i = 0.0, covered = 0.0;

  void add_regions(const NovelView& nv, const NovelView& ni, const ImageF& truth, const ImageU8& sil) {
    const int w = truth.width(), h = truth.height();
    for (int rgn = 0; rgn < 4; ++rgn)
      for (int band = 0; band < 2; ++band) {
        ImageU8 mask(w, h, 1, 0);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            mask.at(x, y) = (nv.unseen.at(x, y) ? 2 : 0) + (ni.unseen.at(x, y) ? 1 : 0) == rgn && (band == 0 || sil.at(x, y));
        region[rgn][band][0].add(compare_images(nv.color, truth, &mask));
        region[rgn][band][1].add(compare_images(ni.color, truth, &mask));
      }
    region_total += double(w) * double(h);
  }
};

// One view's errors added to the pools; its row of the per-view table.
std::vector<std::variant<std::string, double>> add_view(Errors& e, size_t i, const NovelView& nv, const NovelView& ni,
                                                        const ImageF& truth, const ImageU8& sil) {
  ImageU8 seen(truth.width(), truth.height(), 1, 0);
  for (size_t p = 0; p < seen.data().size(); ++p) seen.data()[p] = !nv.unseen.data()[p] && !ni.unseen.data()[p];
  const ImageError ev = compare_images(nv.color, truth), ei = compare_images(ni.color, truth);
  const ImageError sv = compare_images(nv.color, truth, &sil), si = compare_images(ni.color, truth, &sil);
  e.all_v.add(ev);
  e.all_i.add(ei);
  e.sil_v.add(sv);
  e.sil_i.add(si);
  e.seen_v.add(compare_images(nv.color, truth, &seen));
  e.seen_i.add(compare_images(ni.color, truth, &seen));
  const ImageU8 sil_seen = masked(sil, seen);
  e.silseen_v.add(compare_images(nv.color, truth, &sil_seen));
  e.silseen_i.add(compare_images(ni.color, truth, &sil_seen));
  e.add_regions(nv, ni, truth, sil);
  e.holes_v += double(nv.holes);
  e.holes_i += double(ni.holes);
  e.covered += double(nv.covered);
  return {double(i), ev.psnr_db, ei.psnr_db, ev.mae_avg, ei.mae_avg, sv.mae_avg, si.mae_avg,
          100.0 * double(nv.holes) / double(std::max<size_t>(1, nv.covered)), nv.raster_ms + nv.blend_ms};
}

// The photographs' silhouette edges (visibility maps of the cameras the mapping used) lifted
// onto the polygons on both sides, all photographs in order.
std::vector<LiftedEdge> photograph_silhouettes(const GibrModel& g) {
  std::vector<std::vector<LiftedEdge>> per(g.cameras.size());
  parallel_for(per.size(), 1, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i)
      per[i] = lift_silhouettes(trace_visibility_map(g.winged_pair, g.cameras[i]), g.cameras[i], g.model, uint32_t(i));
  });
  std::vector<LiftedEdge> out;
  for (const auto& p : per) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// Pixels within 2 px of the view's silhouettes (`sil`) or of the silhouette edges of the
// photographs the view blends first (k) on each polygon, reprojected where the view sees them.
ImageU8 reprojected_band(const GibrModel& g, std::span<const LiftedEdge> edges, const Camera& cam, int k,
                         const ImageU8& sil) {
  const std::vector<LiftedEdge> blended = blended_edges(edges, g.maps, g.model, cam.position, k);
  ImageU8 band = reprojected_edge_mask(blended, cam, *g.rays, 2.0, g.model.scale);
  for (size_t p = 0; p < band.data().size(); ++p) band.data()[p] = band.data()[p] || sil.data()[p];
  return band;
}

void write_view_images(const StudyOutput& out, Results& results, size_t i, const NovelView& nv, const NovelView& ni,
                       const ImageF& truth) {
  if (i == 0 && out.keeps()) {
    keep_image(out, "novel_vismap", nv.color);
    keep_image(out, "novel_itembuffer", ni.color);
    keep_image(out, "truth", truth);
    keep_image(out, "error_vismap", error_heatmap(error_image(nv.color, truth), kErrorHeatmapMax));
    keep_image(out, "error_itembuffer", error_heatmap(error_image(ni.color, truth), kErrorHeatmapMax));
  }
  if (!out.writes()) return;
  const std::filesystem::path views = out.dir / "views";
  std::filesystem::create_directories(views);
  write_png_linear(views / numbered("vismap", i, ".png"), nv.color);
  write_png_linear(views / numbered("itembuffer", i, ".png"), ni.color);
  write_png_linear(views / numbered("truth", i, ".png"), truth);
  write_png_linear(views / numbered("error_vismap", i, ".png"),
                   error_heatmap(error_image(nv.color, truth), kErrorHeatmapMax));
  write_png_linear(views / numbered("error_itembuffer", i, ".png"),
                   error_heatmap(error_image(ni.color, truth), kErrorHeatmapMax));
  ImageU8 unseen_png(nv.unseen.width(), nv.unseen.height(), 1, 0);
  for (size_t p = 0; p < unseen_png.data().size(); ++p) unseen_png.data()[p] = nv.unseen.data()[p] ? 255 : 0;
  write_png(views / numbered("unseen_vismap", i, ".png"), unseen_png);
  if (i == 0)
    results.images = {{"novel_vismap", "views/vismap_000.png"}, {"novel_itembuffer", "views/itembuffer_000.png"},
                      {"truth", "views/truth_000.png"}, {"error_vismap", "views/error_vismap_000.png"},
                      {"error_itembuffer", "views/error_itembuffer_000.png"}};
}

void add_error_metrics(Results& results, const Errors& e) {
  auto& m = results.metrics;
  m["psnr_vismap"] = e.all_v.psnr();
  m["psnr_itembuffer"] = e.all_i.psnr();
  m["mae_vismap"] = e.all_v.mae();
  m["mae_itembuffer"] = e.all_i.mae();
  m["silhouette_mae_vismap"] = e.sil_v.mae();
  m["silhouette_mae_itembuffer"] = e.sil_i.mae();
  m["silhouette_psnr_vismap"] = e.sil_v.psnr();
  m["silhouette_psnr_itembuffer"] = e.sil_i.psnr();
  m["silhouette_mae_seen_vismap"] = e.silseen_v.mae();
  m["silhouette_mae_seen_itembuffer"] = e.silseen_i.mae();
  m["psnr_seen_vismap"] = e.seen_v.psnr();
  m["psnr_seen_itembuffer"] = e.seen_i.psnr();
  m["unseen_pct_vismap"] = 100.0 * e.holes_v / std::max(1.0, e.covered);
  m["unseen_pct_itembuffer"] = 100.0 * e.holes_i / std::max(1.0, e.covered);
  m["reprojected_silhouette_mae_vismap"] = e.band_v.mae();
  m["reprojected_silhouette_mae_itembuffer"] = e.band_i.mae();
  m["reprojected_silhouette_psnr_vismap"] = e.band_v.psnr();
  m["reprojected_silhouette_psnr_itembuffer"] = e.band_i.psnr();
  m["reprojected_silhouette_pct"] = 100.0 * e.band_v.pixels / std::max(1.0, e.region_total);
}

// Phase 4's times: metrics and the rows of the time-per-phase table.
void add_timing_results(Results& results, const Timings& t, int supersample, Table& phases) {
  auto& m = results.metrics;
  const double med = median(t.frame_ms);
  m["novel_view_cpu_ms"] = median(t.frame_cpu_ms);
  phases.rows.push_back({std::string("4 novel view (median per frame, visibility-map maps)"), med});
  phases.rows.push_back(
      {std::string("4 novel view, process CPU time (median per frame, all threads)"), m["novel_view_cpu_ms"]});
  phases.rows.push_back({std::string("ground truth (reference renders, all views)"), t.truth_ms});
  m["novel_view_ms"] = med;
  m["novel_view_fps"] = med > 0 ? 1000.0 / med : 0.0;
  m["novel_view_ss"] = double(supersample);
  if (t.frame_ms_1spp.empty()) return;
  const double med1 = median(t.frame_ms_1spp);
  m["novel_view_ms_1spp"] = med1;
  m["novel_view_fps_1spp"] = med1 > 0 ? 1000.0 / med1 : 0.0;
  phases.rows.push_back({std::string("4 novel view at 1 sample per pixel (median per frame, for comparison)"), med1});
}

void add_selfcheck_metrics(Results& results, const GibrModel& g) {
  auto& m = results.metrics;
  const double photos = double(g.cameras.size());
  m["bsp_ms"] = g.stats.bsp.build_ms;
  m["vismap_ms_avg"] = g.stats.vismap_ms / photos;
  m["silhouette_edges_avg"] = g.stats.silhouette_edges_avg;
  m["maps_failed_selfcheck"] = double(g.stats.maps_failed_selfcheck);
  m["selfcheck_ms_avg"] = g.stats.selfcheck_ms / photos;
}

Table summary_table(Results& results, const std::string& name, size_t views, size_t photos) {
  auto& m = results.metrics;
  return {"novel views vs ground truth (" + name + ", " + std::to_string(views) + " views, " + std::to_string(photos) +
              " photos)",
          {"mapping", "PSNR dB", "MAE", "PSNR ≤2px silhouettes", "MAE ≤2px silhouettes", "PSNR seen",
           "MAE ≤2px silhouettes, seen", "unseen %"},
          {{std::string("visibility map"), m["psnr_vismap"], m["mae_vismap"], m["silhouette_psnr_vismap"],
            m["silhouette_mae_vismap"], m["psnr_seen_vismap"], m["silhouette_mae_seen_vismap"], m["unseen_pct_vismap"]},
           {std::string("item buffer"), m["psnr_itembuffer"], m["mae_itembuffer"], m["silhouette_psnr_itembuffer"],
            m["silhouette_mae_itembuffer"], m["psnr_seen_itembuffer"], m["silhouette_mae_seen_itembuffer"],
            m["unseen_pct_itembuffer"]}}};
}

Table region_table(const Errors& e, const std::string& name) {
  Table regions{"error by region (" + name + ", pooled over views; % of all pixels)",
                {"region", "pixels %", "MAE vismap", "MAE itembuffer", "≤2px sil. pixels %", "≤2px sil. MAE vismap",
                 "≤2px sil. MAE itembuffer"},
                {}};
  const char* region_names[4] = {"both mappings saw", "vis-map saw, item-buffer hole", "item-buffer saw, vis-map hole",
                                 "both holes"};
  const double total = std::max(1.0, e.region_total);
  for (int rgn = 0; rgn < 4; ++rgn) {
    const auto& r = e.region[rgn];
    regions.rows.push_back({std::string(region_names[rgn]), 100.0 * r[0][0].pixels / total, r[0][0].mae(),
                            r[0][1].mae(), 100.0 * r[1][0].pixels / total, r[1][0].mae(), r[1][1].mae()});
  }
  return regions;
}

// Phases 1–3 with both mappings; their self-check failures warned about on stderr.
GibrModel build_model(const Scene& scene, const GibrOptions& o) {
  GibrModel g = build_gibr_model(scene, gibr_model_options(o));
  for (const std::string& failure : g.stats.selfcheck_failures)
    std::fprintf(stderr, "warning: %s: visibility map of %s (failed its self-check)\n", scene.name.c_str(),
                 failure.c_str());
  return g;
}

}  // namespace

GibrModelOptions gibr_model_options(const GibrOptions& o) {
  GibrModelOptions mo = o.model;
  mo.item_buffer = true;
  mo.seed = o.seed;
  return mo;
}

const char* gibr_views_name(GibrViews views) {
  switch (views) {
    case GibrViews::Path: return "path";
    case GibrViews::Offpath: return "offpath";
    case GibrViews::Photos: return "photos";
  }
  return "?";
}

GibrViews parse_gibr_views(const std::string& name, const char* flag) {
  for (GibrViews v : kAllViews)
    if (name == gibr_views_name(v)) return v;
  fail_input(std::string(flag) + ": must be 'path', 'offpath' or 'photos' (got '" + name + "')");
}

void validate(const GibrOptions& o) {
  require_in_range(o.frames, 1, 10000, "--frames");
  require_in_range(o.novel_ss, 0, 8, "--novel-ss");
  require_in_range(o.hole_radius, 0, 4096, "--hole-radius");
  require_in_range(o.mixed_reach, 0, 64, "--mixed-reach");
  if (!(o.offpath >= 0.0 && o.offpath <= 1e3)) fail_input("--offpath: must be a distance in meters ≥ 0");
  require_in_range(o.fps_repeat, 1, 1000, "--fps-repeat");
  require_in_range(o.k, 1, 64, "--k");
  validate_camera(look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60, o.width, o.height), "--width/--height");
}

Results run_gibr(const Scene& model_scene, const GibrOptions& o, const StudyOutput& out, Progress* progress) {
  validate(o);
  const GibrModel g = build_model(model_scene, o);
  const std::string& name = model_scene.name;
  Results results;
  Table phases{"time per phase (" + name + ")", {"phase", "ms"}, {}};
  phases.rows.push_back({std::string("photographs (reference renders)"), g.stats.photos_ms});
  write_photos(out, g, o.photo_images);
  Table stats = add_model_results(results, name, g, phases);

  // Phase 4: novel views, ground truth and errors.
  const std::vector<Camera> views = novel_cameras(g, model_scene.camera_paths.front(), o);
  Renderer r;
  r.nvo.k = o.k;
  r.nvo.hole_radius = o.hole_radius;
  r.nvo.mixed_reach = o.mixed_reach;
  r.nvo.supersample = o.novel_ss > 0 ? o.novel_ss : o.model.supersample;
  r.nvo1 = r.nvo;
  r.nvo1.supersample = 1;
  Timings t;
  Errors e;
  Table per_view{"novel views of " + name + " ('" + gibr_views_name(o.views) + "')",
                 {"view", "psnr vismap", "psnr itembuffer", "mae vismap", "mae itembuffer", "sil mae vismap",
                  "sil mae itembuffer", "unseen % vismap", "ms vismap"},
                 {}};
  const std::vector<LiftedEdge> photo_edges = photograph_silhouettes(g);
  if (progress) progress->begin("novel views of " + name, int(views.size()));
  for (size_t i = 0; i < views.size(); ++i) {
    if (progress) progress->step("view " + std::to_string(i));
    const Camera& cam = views[i];
    const auto [nv, ni] = render_views(g, cam, o.fps_repeat, r, t);
    Stopwatch w;
    const ImageF truth = render_photo(g.scene, *g.rays, cam, o.model.supersample, derive_seed(o.seed, i, 2));
    t.truth_ms += w.elapsed_ms();
    const ImageU8 sil = silhouette_pixel_mask(trace_visibility_map(g.winged_pair, cam), 2.0);
    per_view.rows.push_back(add_view(e, i, nv, ni, truth, sil));
    const ImageU8 band = reprojected_band(g, photo_edges, cam, o.k, sil);
    e.band_v.add(compare_images(nv.color, truth, &band));
    e.band_i.add(compare_images(ni.color, truth, &band));
    write_view_images(out, results, i, nv, ni, truth);
  }
  if (progress) progress->end();
  add_timing_results(results, t, r.nvo.supersample, phases);
  add_error_metrics(results, e);
  add_selfcheck_metrics(results, g);
  results.tables = {summary_table(results, name, views.size(), g.cameras.size()), region_table(e, name), stats, phases,
                    per_view};
  return results;
}

}  // namespace proxima::study
