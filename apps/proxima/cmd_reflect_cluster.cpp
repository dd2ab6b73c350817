// `proxima reflect --method cluster`: flags → study::ClusterReflectOptions → the study
// (study/cluster_reflect.h) → results.json.
#include "cmd_reflect_cluster.h"

#include "scene_study.h"

namespace proxima::cli {

namespace {

constexpr const char* kGroup = "cluster (--method cluster)";

// Which frames run and what is written of them (temporal reads --frames, --frame-step and
// --image-frame too).
void add_frame_flags(CLI::App* app, ClusterReflectFlags& f) {
  app->add_option("--frames", f.frames,
                  "cluster, temporal: with --path and no --frame, the path is divided into N frames (0 = its "
                  "own count)")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option("--frame-step", f.frame_step, "cluster, temporal: render every N-th of those frames")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option(
         "--image-frame", f.image_frame,
         "cluster, temporal: frame whose images are written (-1 = cluster: the first rendered; temporal: "
         "the first that reuses a key frame)")
      ->capture_default_str()
      ->group(kGroup);
  app->add_flag(
         "--full-reference", f.full_reference,
         "cluster: with --compare, also render_reference (shadows, jittered area-light samples, 1 bounce); "
         "untimed")
      ->group(kGroup);
}

// The method's own parameters: sampling, clustering, cluster images, marching.
void add_method_flags(CLI::App* app, ClusterReflectFlags& f) {
  app->add_option("--ss", f.reflection.supersample,
                  "cluster: K×K samples per pixel (the reference's sub-pixel grid)")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option("--theta-bins", f.cluster.clustering.max_theta_bins, "cluster: MAXTHETABINS")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option("--phi-bins", f.cluster.clustering.max_phi_bins, "cluster: MAXPHIBINS")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option(
         "--min-bin-scale", f.cluster.clustering.min_bin_scale,
         "cluster: lower bound of a reflector's bin scale per axis (0..1; 1 = 13×8 bins for every reflector)")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option("--resolution-scale", f.cluster.resolution_scale,
                  "cluster: image texels per pixel footprint")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option(
         "--second-layer", f.cluster.second_layer,
         "cluster: glossy and curved clusters get a second depth layer that rays hidden behind a nearer "
         "surface are marched in (true/false)")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option("--own-exact", f.cluster.own_exact,
                  "cluster: rays of curved clusters are intersected exactly with their own reflector's triangles "
                  "(true) or marched in its rasterized own layer (false)")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option(
         "--march-block", f.cluster.march_block,
         "cluster: block size of the depth minima the march skips with (0 = texel by texel; same result)")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option("--glossy-march-coarse", f.cluster.glossy_march_coarse,
                  "cluster: glossy clusters' lobe rays march an image of the nearest depth per B×B texels (1 = full image)")
      ->capture_default_str()
      ->group(kGroup);
  app->add_option("--lod", f.cluster.lod_texels,
                  "cluster: draw each object at the coarsest level of detail whose cell is at most this many texel "
                  "footprints (0 = exact triangles)")
      ->capture_default_str()
      ->group(kGroup);
}

}  // namespace

void add_cluster_reflect_flags(CLI::App* app, ClusterReflectFlags& f) {
  add_frame_flags(app, f);
  add_method_flags(app, f);
}

int run_cluster_reflect(const ClusterReflectFlags& f) {
  study::ClusterReflectOptions o = f;
  set_common_options(f.common, o);
  o.reflection.seed = f.common.seed;
  return publish_study(run_scene_study(f.common, o, study::run_cluster_reflect));
}

}  // namespace proxima::cli
