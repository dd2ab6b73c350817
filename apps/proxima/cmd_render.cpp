// `proxima render`: the reference (ray-traced) image of a scene plus its EXR buffers
// (proxima/study/reference.h).
#include "command.h"
#include "proxima/study/reference.h"
#include "scene_study.h"

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

}  // namespace

Command register_render(CLI::App& root) {
  static RenderFlags f;
  auto* app = root.add_subcommand("render", "render the ray-traced reference image of a scene");
  add_common_flags(app, f.common, {.scene = "cornell", .camera = &f.options.camera});
  add_sampling_flags(app, f.options);
  return {app, [] {
            set_common_options(f.common, f.options);
            return publish_study(run_scene_study(f.common, f.options, study::run_reference));
          }};
}

}  // namespace proxima::cli
