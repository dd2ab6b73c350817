// `proxima reflect`: reflections through environment maps with distance (plain, rectified,
// average, layered; study/envmap_reflect.h, docs/envmap.md) against the Embree reference;
// `--method cluster` (and `--method ssr`: the cluster study with screen-space reflections beside
// it) and `--method temporal` run cmd_reflect_cluster.cpp and
// cmd_reflect_temporal.cpp with the flags this command shares with them.
#include <string>

#include "cmd_reflect_cluster.h"
#include "cmd_reflect_temporal.h"
#include "command.h"
#include "proxima/core/error.h"
#include "proxima/study/envmap_reflect.h"
#include "scene_study.h"

namespace proxima::cli {

namespace {

struct ReflectFlags {
  CommonOptions common;
  study::EnvmapReflectOptions envmap;  // --method, the camera and the env-map flags
  ClusterReflectFlags cluster;         // --method cluster (cmd_reflect_cluster.h)
  TemporalReflectFlags temporal;       // --method temporal (cmd_reflect_temporal.h)
};

void check_method(const std::string& method) {
  std::string names;
  for (const char* m : study::kEnvmapReflectMethods) {
    if (method == m) return;
    names += std::string(m) + ", ";
  }
  if (method != "cluster" && method != "ssr" && method != "temporal")
    fail_input("--method: '" + method + "' is not one of " + names + "cluster, ssr, temporal");
}

void add_envmap_flags(CLI::App* app, study::EnvmapReflectOptions& o) {
  app->add_option("--method", o.method, "envmap | rectified | average | layered | boxprobe | reference | cluster | ssr | temporal")
      ->capture_default_str();
  app->add_flag("--compare", o.compare,
                "render every method and the reference; errors and the timing table (cluster: Embree on the "
                "same rays and rectified env mapping)");
  app->add_option("--d-e", o.d_e, "rectification tolerance d_e in meters")->capture_default_str();
  app->add_option("--distance", o.distance, "search length D in meters (0 = scene bounding-box diagonal)")
      ->capture_default_str();
  app->add_option("--cube-size", o.cube_size, "cube map face resolution")->capture_default_str();
  app->add_option("--angle-step", o.angle_step_deg, "sampling step s of the average distance, degrees")
      ->capture_default_str();
  app->add_option("--edge", o.edge, "edge rule when the search ends beside the environment: black | fallback")
      ->capture_default_str();
  app->add_option("--light-samples", o.light_samples, "N×N samples per area light")->capture_default_str();
  app->add_option("--glossy-rays,--gloss-rays", o.glossy_rays, "rays (lookups) per glossy lobe (cluster: 8)")
      ->capture_default_str();
  app->add_option("--layers", o.layers,
                  "layered: depth layers peeled from the map's center (layer 0 = the ordinary distance map)")
      ->capture_default_str();
  app->add_option("--march-steps", o.march_steps, "layered: ray-march samples per lookup at most")
      ->capture_default_str();
  app->add_option("--max-maps", o.max_maps, "env maps at most: reflectors grouped, one map per group (1 = one shared map)")
      ->capture_default_str();
  app->add_option("--group-parallax", o.group_parallax, "reflectors share a map while its mean parallax is at most this")
      ->capture_default_str();
  app->add_option("--reps", o.reps,
                  "timed frames per method, round-robin over the methods (median reported; cluster: 1 per frame)")
      ->capture_default_str();
}

// --method cluster / ssr: the shared flags into the cluster run; flags not given take the
// cluster method's defaults (512×512 as the thesis, 8 lobe rays, 1 timing repetition).
int run_cluster(const ReflectFlags& f, const CLI::App& app) {
  study::EnvmapReflectOptions shared = f.envmap;  // the env-map comparison's flags, checked alike
  shared.method = "rectified";
  shared.compare = false;
  study::validate(shared);
  ClusterReflectFlags c = f.cluster;
  c.common = f.common;
  if (app.count("--width") == 0) c.common.width = 512;
  if (app.count("--height") == 0) c.common.height = c.common.width;
  c.camera = f.envmap.camera;
  c.frame_given = app.count("--frame") > 0;
  c.compare = f.envmap.compare;
  c.reps = app.count("--reps") > 0 ? f.envmap.reps : 1;
  c.reflection.glossy_rays = app.count("--glossy-rays") > 0 ? f.envmap.glossy_rays : 8;
  c.reflection.area_light_samples = f.envmap.light_samples;
  c.cube_size = f.envmap.cube_size;
  c.envmap_groups = {f.envmap.group_parallax, f.envmap.max_maps};
  c.d_e = f.envmap.d_e;
  c.distance = f.envmap.distance;
  c.edge_fallback = f.envmap.edge == "fallback";
  c.ssr = f.envmap.method == "ssr";
  return run_cluster_reflect(c);
}

// --method temporal: the path, --frames, --frame-step and --image-frame (the cluster
// group's flags) and the shared shading flags into the temporal run.
int run_temporal(const ReflectFlags& f) {
  const CameraChoice& camera = f.envmap.camera;
  if (!camera.camera.empty()) fail_input("--camera: --method temporal follows --path");
  if (camera.frame != 0) fail_input("--frame: --method temporal renders the whole path (see --frames)");
  TemporalReflectFlags t = f.temporal;
  t.frames = f.cluster.frames;
  t.frame_step = f.cluster.frame_step;
  t.image_frame = f.cluster.image_frame;
  TemporalReflectRun run{f.common, camera.path, f.envmap.compare, f.envmap.light_samples, f.envmap.glossy_rays, t};
  return run_temporal_reflect(run);
}

int run_reflect(ReflectFlags& f, const CLI::App& app) {
  check_method(f.envmap.method);
  if (f.envmap.method == "temporal") return run_temporal(f);
  if (f.envmap.method == "cluster" || f.envmap.method == "ssr") return run_cluster(f, app);
  set_common_options(f.common, f.envmap);
  return publish_study(run_scene_study(f.common, f.envmap, study::run_envmap_reflect));
}

}  // namespace

Command register_reflect(CLI::App& root) {
  static ReflectFlags f;
  auto* app = root.add_subcommand(
      "reflect",
      "reflections through environment maps with distance (plain, rectified, average, layered) or clustered "
      "depth images (cluster) vs Embree");
  f.common.width = 1024;
  f.common.height = 768;
  add_common_flags(app, f.common, {.scene = "room-reflector", .camera = &f.envmap.camera});
  add_envmap_flags(app, f.envmap);
  // --frames, --frame-step and --image-frame are the cluster group's; temporal reads them too.
  add_cluster_reflect_flags(app, f.cluster);
  add_temporal_reflect_flags(app, f.temporal);
  return {app, [app] { return run_reflect(f, *app); }};
}

}  // namespace proxima::cli
