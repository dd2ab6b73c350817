// `proxima bench view`: frame rate of every viewer technique while the camera moves,
// headless, plus the refine frame and optionally the error vs the reference
// (proxima/viewer/viewer_bench.h).
#include "command.h"
#include "view_flags.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/load.h"
#include "proxima/viewer/viewer_bench.h"

namespace proxima::cli {

namespace {

struct BenchViewFlags {
  ViewSetup setup;
  std::string out = "out/bench-view";
  ViewerBenchOptions options;
};

void add_bench_flags(CLI::App* app, BenchViewFlags& f) {
  app->add_option("--out", f.out, "output directory (created if missing)")->capture_default_str();
  app->add_option("--frames", f.options.frames, "moving frames per block")->capture_default_str();
  app->add_option("--rounds", f.options.rounds, "blocks per technique, round-robin")->capture_default_str();
  app->add_option("--techniques", f.options.techniques, "comma-separated subset (default: every available one)")
      ->delimiter(',');
  app->add_flag("--error", f.options.error, "also wait for each technique's reference once still: its MAE (slow)");
}

int run_bench_view(BenchViewFlags& f) {
  ViewerBenchOptions& o = f.options;
  o.camera = f.setup.camera;
  o.width = f.setup.common.width;
  o.height = f.setup.common.height;
  o.seed = f.setup.common.seed;
  o.move_scale = f.setup.move_scale;
  validate_view_flags(f.setup);
  validate(o);
  ThreadLimit limit(f.setup.common.threads);
  const Scene scene = load_scene(f.setup.common.scene);
  pick_camera(scene, o.camera, o.width, o.height);  // a bad camera choice fails before --out exists
  const auto out = prepare_out_dir(f.out);
  return publish_study(out, run_viewer_bench(scene, o, {}));
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
