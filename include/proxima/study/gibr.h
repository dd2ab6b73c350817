// The hybrid geometry- and image-based rendering study (`proxima gibr`, docs/gibr.md): the
// four phases of Funkhouser's system (section 2) on a polygonal model with a walk path —
// synthetic calibrated photographs, (1) BSP → winged pair, (2) a visibility map per
// photograph, (3) radiance maps, (4) novel views, each compared with a reference render —
// with the visibility-map mapping beside the item-buffer (z-buffer) mapping of Debevec et al.
#pragma once

#include <cstdint>
#include <string>

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/gibr/novel_view.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"

namespace proxima::study {

// Where the novel views are: along the walk path (evenly spaced in time, first to last
// key), off it (the path's cameras moved sideways, gibr/photo_set.h offpath_poses), or at
// the first photograph poses (cycling when there are more views than photographs).
enum class GibrViews { Path, Offpath, Photos };
const char* gibr_views_name(GibrViews views);  // "path" | "offpath" | "photos"
// Throws InputError naming `flag` and the valid names for anything else.
GibrViews parse_gibr_views(const std::string& name, const char* flag);

struct GibrOptions {
  int width = 640, height = 480;  // --width, --height: novel views and their ground truth, pixels
  uint64_t seed = 1;              // --seed: photograph poses, textures, photograph and ground-truth samples
  // Phases 1–3 (--photos, --photo-width, --photo-height, --camera-file, --texel, --period,
  // --supersample, --exclude-boundaries, --whole-pixels, --no-unmix); the study sets its
  // `item_buffer` (both mappings are compared) and `seed` (to the seed above).
  gibr::GibrModelOptions model;
  GibrViews views = GibrViews::Path;  // --views
  int frames = 10;                    // --frames: novel views rendered and compared, 1..10000
  int k = 3;                          // --k: photographs blended per pixel, 1..64
  int novel_ss = 0;                   // --novel-ss: s×s samples per novel-view pixel, 0..8; 0 = model.supersample
  int hole_radius = gibr::NovelViewOptions{}.hole_radius;  // --hole-radius: texels searched around a hole, 0..4096
  int mixed_reach = gibr::NovelViewOptions{}.mixed_reach;  // --mixed-reach: local mixed samples first for holes, 0..64
  double offpath = 0.5;               // --offpath: meters the Offpath views move off the path, 0..1000
  bool photo_images = true;           // --no-photo-images clears it: photos/photo_NNN.png
  int fps_repeat = 3;                 // --fps-repeat: timed renders per novel view (median → novel_view_fps), 1..1000
};

// Throws InputError naming the flag for the fields above outside their ranges and a
// --width/--height that is not a valid image size; the model options are checked by
// build_gibr_model (gibr/gibr_model.h) as run_gibr starts, before any work.
void validate(const GibrOptions& options);

// The model options run_gibr builds with: options.model with item_buffer and the seed set.
gibr::GibrModelOptions gibr_model_options(const GibrOptions& options);

// Builds the model with both mappings (warning on stderr for every photograph's visibility
// map that fails its self-check), renders `frames` novel views with each mapping (timed
// `fps_repeat` times with the visibility-map maps; also at 1 sample per pixel when
// supersampled) and a ground truth per view, and compares them: overall, within 2 px of the
// view's silhouettes, where both mappings saw the surface, and by region (which mapping
// left a hole there). Errors on the 0–255 display scale, pooled over the views.
// Metrics: texel_m, photos, layers_vismap, samples_{vismap,itembuffer},
// samples_unmixed_vismap, samples_extrapolated_vismap, texels_covered_pct_vismap,
// pixels_mapped_{vismap,itembuffer}, and per mapping ({vismap,itembuffer}) psnr, mae,
// silhouette_mae, silhouette_psnr, silhouette_mae_seen, psnr_seen, unseen_pct,
// reprojected_silhouette_{mae,psnr} (within 2 px of the view's silhouettes or of a
// photograph's silhouette edges reprojected where the view sees them, gibr/silhouette_band.h)
// and reprojected_silhouette_pct (that band's share of the pixels); novel_view_ms,
// novel_view_fps, novel_view_cpu_ms, novel_view_ss, novel_view_{ms,fps}_1spp (supersampled
// only), bsp_ms, vismap_ms_avg, silhouette_edges_avg, maps_failed_selfcheck,
// selfcheck_ms_avg. Tables: summary, error by region, radiance maps, time per phase, per view.
// Files (out.writes()): photos/cameras.json (+ photos/photo_NNN.png with photo_images),
// views/{vismap,itembuffer,truth,error_vismap,error_itembuffer,unseen_vismap}_NNN.png, the
// error maps on the kErrorHeatmapMax scale; roles novel_vismap, novel_itembuffer, truth,
// error_vismap, error_itembuffer for view 0. Bad model options, a scene without a camera
// path or a bad camera file throw InputError before anything is written.
// Deterministic for a seed (timings aside) at any thread count.
Results run_gibr(const Scene& scene, const GibrOptions& options, const StudyOutput& out, Progress* progress = nullptr);

}  // namespace proxima::study
