// `proxima shadows`: the soft-shadow study (proxima/study/shadows.h; docs/shadows.md) from
// the command line.
#include <string>
#include <vector>

#include "command.h"
#include "proxima/study/shadows.h"
#include "scene_study.h"

namespace proxima::cli {

namespace {

struct ShadowsFlags {
  CommonOptions common;
  study::ShadowsOptions options;
  // The enum flags as given, parsed into `options` before the run.
  std::vector<std::string> samplings;
  std::string redundancy, reconstruction;
  bool no_images = false;
};

void add_method_flags(CLI::App* app, ShadowsFlags& f) {
  for (ShadowSampling s : f.options.samplings) f.samplings.push_back(shadow_sampling_name(s));
  f.redundancy = redundancy_name(f.options.redundancy);
  f.reconstruction = reconstruction_name(f.options.reconstruction);
  app->add_option("--sampling", f.samplings,
                  "nrr|conventional|peeling|geometry; several, comma-separated, share the ground truth")
      ->delimiter(',')
      ->capture_default_str();
  app->add_option("--redundancy", f.redundancy, "pixel|visibility: NRR's redundancy test")->capture_default_str();
  app->add_option("--reconstruction", f.reconstruction, "hybrid (Algorithm 4) | conventional mesh")
      ->capture_default_str();
}

void add_light_flags(CLI::App* app, study::ShadowsOptions& o) {
  app->add_option("--light-size", o.light_size, "light diagonal / scene bounding-box diagonal")->capture_default_str();
  app->add_option("--light-samples", o.light_samples, "n: the light is sampled n x n")->capture_default_str();
  app->add_option("--ref-res", o.ref_res, "reference depth images, pixels (square)")->capture_default_str();
  app->add_option("--out-res", o.out_res, "output image, pixels (square)")->capture_default_str();
  app->add_option("--shadow-res", o.shadow_res, "shadow-map texel density: of a map this side over the light field")
      ->capture_default_str();
  app->add_flag("--full-maps", o.full_maps, "shadow maps cover the whole light field (not fitted to the receivers)");
  app->add_option("--shadow-footprint", o.shadow_footprint, "texels per receiver footprint (0: --shadow-res alone)")
      ->capture_default_str();
  app->add_flag("--no-rays", o.no_rays, "skip the Embree shadow-ray ground truth");
}

// The options the study runs with: the enum names parsed.
const study::ShadowsOptions& finish_options(ShadowsFlags& f) {
  study::ShadowsOptions& o = f.options;
  o.samplings.clear();
  for (const std::string& s : f.samplings) o.samplings.push_back(parse_shadow_sampling(s, "--sampling"));
  o.redundancy = parse_redundancy(f.redundancy, "--redundancy");
  o.reconstruction = parse_reconstruction(f.reconstruction, "--reconstruction");
  return o;
}

}  // namespace

Command register_shadows(CLI::App& root) {
  static ShadowsFlags f;
  auto* app = root.add_subcommand("shadows", "soft shadows from an area light through depth images reconstructed into "
                                             "meshes (NRR, conventional, peeling), vs shadow maps of the geometry and "
                                             "Embree shadow rays");
  add_common_flags(app, f.common, {.scene = "nest", .camera = &f.options.camera, .size = false, .seed = false});
  add_method_flags(app, f);
  add_light_flags(app, f.options);
  app->add_flag("--no-images", f.no_images, "write results.json only");

  return {app, [] {
            const study::ShadowsOptions& options = finish_options(f);
            return publish_study(run_scene_study(f.common, options, study::run_shadows, {.images = !f.no_images}));
          }};
}

}  // namespace proxima::cli
