// `proxima render`: the reference (ray-traced) image of a scene plus its EXR buffers
// (proxima/study/reference.h).
#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/load.h"
#include "proxima/study/reference.h"

namespace proxima::cli {

namespace {

struct RenderFlags {
  CommonOptions common;
  study::ReferenceStudyOptions options;
};

void add_sampling_flags(CLI::App* app, study::ReferenceStudyOptions& o) {
  app->add_option("--spp", o.supersample, "supersampling: K×K stratified samples per pixel")->capture_default_str();
  app->add_option("--light-samples", o.light_samples, "N×N samples per area light")->capture_default_str();
  app->add_option("--glossy-rays", o.glossy_rays, "rays per glossy lobe")->capture_default_str();
  app->add_option("--bounces", o.bounces, "reflection depth (0 = none)")->capture_default_str();
  app->add_option("--time", o.time, "pose time in seconds for animated scenes");
}

int run_render(RenderFlags& f) {
  study::ReferenceStudyOptions& o = f.options;
  o.width = f.common.width;
  o.height = f.common.height;
  o.seed = f.common.seed;
  study::validate(o);
  if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
  ThreadLimit limit(f.common.threads);
  const Scene scene = load_scene(f.common.scene);
  pick_camera(scene, o.camera, o.width, o.height);  // a bad camera choice fails before --out exists
  const auto out = prepare_out_dir(f.common.out);
  return publish_study(out, study::run_reference(scene, o, {out}));
}

}  // namespace

Command register_render(CLI::App& root) {
  static RenderFlags f;
  auto* app = root.add_subcommand("render", "render the ray-traced reference image of a scene");
  add_scene_flag(app, f.common, "cornell");
  add_camera_flags(app, f.options.camera);
  add_size_flags(app, f.common);
  add_threads_flag(app, f.common);
  add_seed_flag(app, f.common);
  add_out_flag(app, f.common, true);
  add_sampling_flags(app, f.options);
  return {app, [] { return run_render(f); }};
}

}  // namespace proxima::cli
