// `proxima reflect --method temporal`: flags → study::TemporalReflectOptions → the study
// (study/temporal_reflect.h) → results.json.
#include "cmd_reflect_temporal.h"

#include <iostream>

#include "scene_study.h"

namespace proxima::cli {

namespace {

// When reuse gives way to tracing: key frames, unreliable warp triangles, blend risk.
void add_reuse_flags(CLI::App* app, TemporalReflectFlags& f) {
  app->add_option("--threshold", f.threshold,
                  "temporal: next frame is a key frame when more than this fraction of reflective pixels was "
                  "recomputed")
      ->capture_default_str();
  app->add_option("--stretch-limit", f.stretch_limit,
                  "temporal: warped grid triangles stretched more than this (area ratio) are unreliable")
      ->capture_default_str();
  app->add_option(
         "--spread-limit", f.spread_limit,
         "temporal: warped grid triangles on a reflector that spreads neighbouring pixels' reflection "
         "directions more than this many times their view angle (curved mirrors) are unreliable; inf = off")
      ->capture_default_str();
  app->add_option(
         "--curved-contrast", f.curved_contrast,
         "temporal: ... only where s*Lr differs between neighbouring key pixels by more than this (linear)")
      ->capture_default_str();
  app->add_option("--edge-contrast", f.edge_contrast,
                  "temporal: warped grid triangles whose corners' s*Lr differ by more than this (linear, any "
                  "channel) span an edge of the reflected image and follow --edge-rule; inf = off")
      ->capture_default_str();
  app->add_option("--edge-rule", f.edge_rule,
                  "temporal: on such an edge a reused pixel takes its nearest corner's Lr instead of a blend "
                  "(nearest) or is recomputed (recompute)")
      ->capture_default_str();
  app->add_flag(
      "--recompute-splats", f.recompute_splats,
      "temporal: key samples no warp triangle reached (splatted as points) are unreliable, so recomputed");
  app->add_option(
         "--blend-error", f.blend_error,
         "temporal: a reused pixel whose expected display error (0-255: sum over the key samples it blends "
         "of weight x |D(base + s*Lr_k) - D(base + s*value)|, D = sRGB, any channel) exceeds this is "
         "recomputed; inf = off (the thesis' method; docs/temporal.md)")
      ->capture_default_str();
  app->add_option(
         "--refine-error", f.refine_error,
         "temporal: where a recomputed pixel's reuse value (the blend-error rule's) turns out to err by "
         "more than this (0-255, any channel), its reused neighbours on the same reflector are recomputed "
         "too, and theirs in turn, until none is added; inf = off (docs/temporal.md)")
      ->capture_default_str();
  app->add_option(
         "--learn-error", f.learn_error,
         "temporal: where a recomputed pixel's reuse value turns out to err by more than this (0-255, any "
         "channel), later frames of the key cycle recompute the pixels that would reuse the same key pixel, "
         "and observe them in turn; inf = off (docs/temporal.md)")
      ->capture_default_str();
  app->add_option(
         "--keyframe-cost", f.keyframe_cost,
         "temporal: also start a key frame once a reuse frame's work (traced rays + this many rays per "
         "reflective key pixel for best match, warp and reprojection) reaches the average work per frame "
         "since the last key frame, full trace = 1; 0 = off (the thesis' threshold policy alone)")
      ->capture_default_str();
}

// The match and warp's geometry, lobe seeding, and the comparison's extras.
void add_method_flags(CLI::App* app, TemporalReflectFlags& f) {
  app->add_flag(
      "--match-extrapolate", f.match_extrapolate,
      "temporal: the best match also tries the previous offset plus its last change (steady motion) "
      "and starts from the closer of the two");
  app->add_option(
         "--depth-discontinuity", f.depth_discontinuity,
         "temporal: warp grid corners whose s.d or s.d + s.r differ by more than this fraction are not "
         "connected (their gap is recomputed)")
      ->capture_default_str();
  app->add_option(
         "--lobe-seed-cell", f.lobe_seed_cell,
         "temporal: > 0 seeds glossy lobe rays by the surface point (world cell of this edge x the scene "
         "diagonal) instead of the pixel, in the temporal method and the reference alike; 0 = per pixel")
      ->capture_default_str();
  app->add_flag("--breakdown", f.breakdown,
                "temporal, with --compare: error by pixel class and key-frame age, and the reference's own "
                "noise against itself traced with seed+1 (one more G-buffer and trace per frame)");
  app->add_option("--reference-rays", f.reference_rays,
                  "temporal, with --compare: also errors against a reference with this many glossy lobe rays "
                  "(0 = off)")
      ->capture_default_str();
}

}  // namespace

void add_temporal_reflect_flags(CLI::App* app, TemporalReflectFlags& f) {
  add_reuse_flags(app, f);
  add_method_flags(app, f);
}

int run_temporal_reflect(const TemporalReflectRun& r) {
  study::TemporalReflectOptions o = r.temporal;
  set_common_options(r.common, o);
  o.path = r.path;
  o.compare = r.compare;
  o.light_samples = r.light_samples;
  o.glossy_rays = r.glossy_rays;
  SceneStudyRun run = run_scene_study(r.common, o, study::run_temporal_reflect);
  // Everything into results.json; the per-frame table (one row per frame) is not printed.
  Results printed = run.results;
  std::erase_if(printed.tables, [](const Table& t) { return t.title == "Per frame"; });
  run.results.command = command_line();
  run.results.threads = active_threads();
  write_results_json(run.out / "results.json", run.results);
  for (const Table& t : printed.tables) std::cout << markdown_table(t) << "\n";
  std::cout << "results: " << (run.out / "results.json").string() << "\n";
  return 0;
}

}  // namespace proxima::cli
