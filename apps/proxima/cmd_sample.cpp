// `proxima sample`: the depth-image sampling study (proxima/study/sampling.h;
// docs/depthimage.md) from the command line.
#include <string>
#include <vector>

#include "command.h"
#include "proxima/study/sampling.h"
#include "scene_study.h"

namespace proxima::cli {

namespace {

struct SampleFlags {
  CommonOptions common;
  study::SamplingOptions options;
  // The enum flags as given, parsed into `options` before the run.
  std::vector<std::string> methods;
  std::string views, redundancy;  // redundancy empty: the study's default
  bool no_images = false;
};

void add_method_flags(CLI::App* app, SampleFlags& f) {
  for (study::SamplingMethod m : f.options.methods) f.methods.push_back(study::sampling_method_name(m));
  f.views = view_shape_name(f.options.views);
  app->add_option("--method", f.methods,
                  "conventional|peeling|nrr-pixel|nrr-visibility; several, comma-separated, share the output frames")
      ->delimiter(',')
      ->capture_default_str();
  app->add_option("--views", f.views, "view set: segment (2 views), triangle (3), rectangle (4)")->capture_default_str();
  app->add_option("--redundancy", f.redundancy,
                  "pixel|visibility: definition the metrics use (default: visibility for nrr-visibility alone, else pixel)");
}

void add_metric_flags(CLI::App* app, SampleFlags& f) {
  study::SamplingOptions& o = f.options;
  app->add_option("--frames", o.frames, "K intermediate output frames for the useful / available metrics")
      ->capture_default_str();
  app->add_option("--radius", o.radius, "distance of the views from the scene camera, m (0 = 8 % of the focus distance)")
      ->capture_default_str();
  app->add_option("--reps", o.reps, "timed repetitions of each method (median reported)")->capture_default_str();
  app->add_flag("--no-images", f.no_images, "write results.json only, no per-image files");
}

// The options the study runs with: the shared flags copied, the enum names parsed.
const study::SamplingOptions& finish_options(CLI::App* app, SampleFlags& f) {
  study::SamplingOptions& o = f.options;
  set_common_options(f.common, o);
  if (app->count("--height") == 0) o.height = f.common.width;
  o.methods.clear();
  for (const std::string& m : f.methods) o.methods.push_back(study::parse_sampling_method(m, "--method"));
  o.views = parse_view_shape(f.views, "--views");
  if (!f.redundancy.empty()) o.redundancy = parse_redundancy(f.redundancy, "--redundancy");
  return o;
}

}  // namespace

Command register_sample(CLI::App& root) {
  static SampleFlags f;
  auto* app = root.add_subcommand("sample", "sample a scene with depth images (conventional, peeling, NRR) and "
                                            "measure redundant / occluded / useful / available samples");
  f.common.width = f.common.height = f.options.width;  // --height defaults to --width (the thesis' images are square)
  add_common_flags(app, f.common, {.scene = "nest", .camera = &f.options.camera});
  add_method_flags(app, f);
  add_metric_flags(app, f);

  return {app, [app] {
            const study::SamplingOptions& options = finish_options(app, f);
            return publish_study(run_scene_study(f.common, options, study::run_sampling, {.images = !f.no_images}));
          }};
}

}  // namespace proxima::cli
