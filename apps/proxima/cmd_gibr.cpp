// `proxima gibr`: hybrid geometry- and image-based rendering, visibility-map mapping against
// the item-buffer mapping (study/gibr.h, docs/gibr.md).
#include "command.h"
#include "proxima/study/gibr.h"
#include "scene_study.h"

namespace proxima::cli {

namespace {

struct GibrFlags {
  CommonOptions common;
  study::GibrOptions options;
  std::string views = "path";  // parsed into options.views
};

// Phases 1–3: the photographs and the radiance maps.
void add_model_flags(CLI::App* app, gibr::GibrModelOptions& m) {
  app->add_option("--photos", m.photos, "calibrated photographs rendered along the walk path")->capture_default_str();
  app->add_option("--photo-width", m.photo_width, "photograph width in pixels")->capture_default_str();
  app->add_option("--photo-height", m.photo_height, "photograph height in pixels")->capture_default_str();
  app->add_option("--camera-file", m.camera_file,
                  "photographs from this camera file (JSON, docs/gibr.md; e.g. a run's photos/cameras.json or real "
                  "photographs of the model) instead of rendering --photos of them");
  app->add_option("--texel", m.texel, "radiance-map texel size in meters (default: per scene, docs/gibr.md)");
  app->add_option("--period", m.period, "texture repeat in meters (default: per scene)");
  app->add_option("--supersample", m.supersample, "k×k samples per photograph / ground-truth pixel")
      ->capture_default_str();
  app->add_flag("--exclude-boundaries", m.exclude_boundaries,
                "visibility-map mapping also drops pixels touching any edge between different polygons");
  app->add_flag("--whole-pixels", m.whole_pixels,
                "visibility-map mapping without exact-visible texels: texels seen only in pixels not mapped onto "
                "their polygon (silhouettes, creases) get no sample");
  app->add_flag("--unmix-two-pass", m.unmix_two_pass,
                "unmixing also takes a side's color from pixels unmixed for it (thin occluders)");
  app->add_option("--photo-yaw", m.photo_yaw_deg, "photographs' view directions turned by up to ± this, degrees")
      ->capture_default_str();
  app->add_option("--photo-backoff", m.photo_backoff, "meters the photographs step back from the walk path")
      ->capture_default_str();
  app->add_option("--calibration-px", m.calibration_px,
                  "calibration error: the mapping's cameras turned by this many pixels from the photographs' poses")
      ->capture_default_str();
  app->add_flag("!--no-unmix", m.unmix,
                "visibility-map mapping without unmixing silhouette pixels: exact-visible texels take colors only "
                "from pixels wholly on their polygon");
}

// Phase 4: the novel views and how they are rendered and timed.
void add_view_flags(CLI::App* app, GibrFlags& f) {
  study::GibrOptions& o = f.options;
  app->add_option("--views", f.views,
                  "novel views: 'path' (along the walk path), 'offpath' (the path's cameras moved sideways by "
                  "--offpath) or 'photos' (at the first photo poses)")
      ->capture_default_str();
  app->add_option("--frames", o.frames, "novel views rendered and compared")->capture_default_str();
  app->add_option("--k", o.k, "photographs blended per pixel")->capture_default_str();
  app->add_option("--novel-ss", o.novel_ss,
                  "s×s samples per novel-view pixel, both mappings (0 = the ground truth's --supersample)")
      ->capture_default_str();
  app->add_option("--hole-radius", o.hole_radius,
                  "texels searched around a novel-view hole for the nearest sample, both mappings (0 = no fill)")
      ->capture_default_str();
  app->add_option("--mixed-reach", o.mixed_reach,
                  "a hole with only mixed samples within this many texels takes them first (0 = off)")
      ->capture_default_str();
  app->add_option("--offpath", o.offpath, "meters the 'offpath' views are moved off the walk path")
      ->capture_default_str();
  app->add_option("--fps-repeat", o.fps_repeat, "timed renders of each novel view (median → novel_view_fps)")
      ->capture_default_str();
  app->add_flag("!--no-photo-images", o.photo_images, "do not write the photographs as PNG");
}

int run(GibrFlags& f) {
  f.options.views = study::parse_gibr_views(f.views, "--views");
  set_common_options(f.common, f.options);
  // A bar on a terminal; logs and pipes get none.
  return publish_study(run_scene_study(f.common, f.options, study::run_gibr, {.log_progress = false}));
}

}  // namespace

Command register_gibr(CLI::App& root) {
  static GibrFlags f;
  auto* app = root.add_subcommand(
      "gibr", "hybrid geometry- and image-based rendering: photos → visibility maps → radiance maps → novel views");
  f.common.width = f.options.width;
  f.common.height = f.options.height;
  add_common_flags(app, f.common, {.scene = "rooms"});
  add_model_flags(app, f.options.model);
  add_view_flags(app, f);
  return {app, [] { return run(f); }};
}

}  // namespace proxima::cli
