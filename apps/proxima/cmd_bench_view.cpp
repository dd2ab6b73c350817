// `proxima bench view`: frame rate of every viewer technique while the camera moves,
// headless, plus the refine frame and optionally the error vs the reference
// (proxima/viewer/viewer_bench.h).
#include "command.h"
#include "proxima/viewer/viewer_bench.h"
#include "scene_study.h"
#include "view_flags.h"

namespace proxima::cli {

namespace {

struct BenchViewFlags {
  ViewSetup setup;
  ViewerBenchOptions options;
};

void add_bench_flags(CLI::App* app, BenchViewFlags& f) {
  f.setup.common.out = "out/bench-view";
  add_out_flag(app, f.setup.common);
  app->add_option("--frames", f.options.frames, "moving frames per block")->capture_default_str();
  app->add_option("--rounds", f.options.rounds, "blocks per technique, round-robin")->capture_default_str();
  app->add_option("--techniques", f.options.techniques, "comma-separated subset (default: every available one)")
      ->delimiter(',');
  app->add_flag("--error", f.options.error, "also wait for each technique's reference once still: its MAE (slow)");
}

int run_bench_view(BenchViewFlags& f) {
  ViewerBenchOptions& o = f.options;
  o.camera = f.setup.camera;
  set_common_options(f.setup.common, o);
  o.move_scale = f.setup.move_scale;
  // validate(o) checks the window size and move scale as validate_view_flags does.
  return publish_study(run_scene_study(f.setup.common, o, run_viewer_bench, {.images = false}));
}

}  // namespace

Command register_bench_view(CLI::App& bench) {
  static BenchViewFlags f;
  auto* app = bench.add_subcommand("view", "viewer techniques: frames/s while moving (headless), refine frame, "
                                           "error vs the reference");
  f.setup.move_scale = f.options.move_scale;
  add_view_flags(app, f.setup, "render at 1/N of the window per side while moving (0 = adaptive)");
  add_bench_flags(app, f);
  return {app, [] { return run_bench_view(f); }};
}

}  // namespace proxima::cli
