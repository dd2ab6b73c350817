// `proxima reflect`: reflections through environment maps with distance (Wang et al. 2012,
// docs/envmap.md) — plain, rectified, average-distance and layered — against the Embree
// reference on the same camera and pixels (mirror, one bounce into the environment);
// `--method cluster` runs the clustered depth images of issue 7 (cmd_reflect_cluster.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cmd_reflect_cluster.h"
#include "cmd_reflect_temporal.h"
#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/trace/direct_light.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/scene/load.h"
#include "proxima/scene/shading.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::cli {

namespace {

struct ReflectFlags {
  CommonOptions common;
  CameraChoice camera;
  std::string method = "rectified";
  bool compare = false;
  float d_e = 0.01f;
  float distance = 0.0f;  // D; 0 = the scene's bounding-box diagonal
  int cube_size = 512;
  float angle_step_deg = 2.0f;
  std::string edge = "black";
  int light_samples = 4;
  int glossy_rays = 16;
  int reps = 3;
  int layers = 3;                    // DistanceCubeLayerOptions::layers
  int march_steps = 64;              // RectifyOptions::max_march_steps
  TemporalReflectFlags temporal;     // --method temporal (cmd_reflect_temporal.h)
};

// Error heat maps saturate here (0–255 units), the same for every method.
constexpr float kHeatmapMax = 64.0f;

// Every method in the order of the results table; "reference" last.
const char* const kMethods[] = {"envmap", "rectified", "average", "layered", "reference"};

EnvmapMethod parse_method(const std::string& name) {
  if (name == "envmap") return EnvmapMethod::Plain;
  if (name == "rectified") return EnvmapMethod::Rectified;
  if (name == "average") return EnvmapMethod::Average;
  return EnvmapMethod::Layered;
}

void validate(const ReflectFlags& f) {
  if (f.method != "cluster" && std::find(std::begin(kMethods), std::end(kMethods), f.method) == std::end(kMethods))
    fail_input("--method: '" + f.method + "' is not one of envmap, rectified, average, layered, reference, cluster");
  if (!(f.d_e > 0.0f) || !std::isfinite(f.d_e)) fail_input("--d-e: must be a positive number");
  if (!(f.distance >= 0.0f) || !std::isfinite(f.distance))
    fail_input("--distance: must be ≥ 0 (0 = scene diagonal)");
  if (f.cube_size < 1 || f.cube_size > 4096) fail_input("--cube-size: must be in 1..4096");
  if (!(f.angle_step_deg > 0.0f && f.angle_step_deg <= 90.0f))
    fail_input("--angle-step: must be in (0, 90] degrees");
  if (f.edge != "black" && f.edge != "fallback") fail_input("--edge: must be black or fallback");
  if (f.light_samples < 1 || f.light_samples > 64) fail_input("--light-samples: must be in 1..64");
  if (f.glossy_rays < 1 || f.glossy_rays > 4096) fail_input("--glossy-rays: must be in 1..4096");
  if (f.reps < 1 || f.reps > 100) fail_input("--reps: must be in 1..100");
  if (f.layers < 1 || f.layers > kMaxDistanceCubeLayers) fail_input("--layers: must be in 1..16");
  if (f.march_steps < 1 || f.march_steps > 4096) fail_input("--march-steps: must be in 1..4096");
  if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
}

// Pixels both the rasterized frame and the reference's item buffer give to a reflector.
ImageU8 comparison_mask(const ReflectorPixels& pixels, const ItemBuffer& item, const Scene& scene,
                        std::span<const uint32_t> reflectors, size_t* count) {
  ImageU8 mask(pixels.triangle.width(), pixels.triangle.height(), 1, 0);
  *count = 0;
  for (size_t i = 0; i < mask.data().size(); ++i) {
    const uint32_t t = item.triangle.data()[i];
    if (pixels.triangle.data()[i] == kNoTriangle || t == kNoTriangle) continue;
    if (std::find(reflectors.begin(), reflectors.end(), scene.triangle_object[t]) == reflectors.end())
      continue;
    mask.data()[i] = 1;
    ++*count;
  }
  return mask;
}

// Per mask pixel, the object the reference's mirror ray from the primary hit meets
// (kNoObject where it escapes): what each method's lookup should have found.
ImageU32 reference_reflected_objects(const Scene& scene, const RayScene& rays, const Camera& camera,
                                     const ItemBuffer& item, const ImageU8& mask) {
  ImageU32 out(camera.width, camera.height, 1, kNoTriangle);  // kNoObject has the same value
  const DirectLight offsets(scene, rays, 1);
  parallel_for(size_t(camera.height), 8, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < camera.width; ++x) {
        if (!mask.at(x, y)) continue;
        const uint32_t t = item.triangle.at(x, y);
        const float u = item.barycentric.at(x, y, 0), v = item.barycentric.at(x, y, 1);
        const vec3 view = triangle_point(scene, t, u, v) - camera.position;
        const SurfacePoint sp = surface_point_seen(scene, t, u, v, view);
        const vec3 dir = glossy_lobe_direction(reflect(glm::normalize(view), sp.n), sp.ng, 0.0f, vec2(0.0f));
        const Hit hit = rays.intersect(Ray{offsets.offset_origin(sp), dir, 0.0f, kInf});
        if (hit.valid()) out.at(x, y) = scene.triangle_object[hit.triangle];
      }
  });
  return out;
}

// Percentage of mask pixels whose looked-up object is the reference's.
double object_match_pct(const ImageU32& objects, const ImageU32& reference, const ImageU8& mask,
                        size_t count) {
  size_t same = 0;
  for (size_t i = 0; i < mask.data().size(); ++i)
    same += mask.data()[i] && objects.data()[i] == reference.data()[i];
  return count ? 100.0 * double(same) / double(count) : 100.0;
}

// --method cluster: the shared flags into the cluster run; flags not given take the
// cluster method's defaults (512×512 as the thesis, 8 lobe rays, 1 timing repetition).
int run_cluster(const ReflectFlags& f, const CLI::App& app, ClusterReflectFlags c) {
  c.common = f.common;
  if (app.count("--width") == 0) c.common.width = 512;
  if (app.count("--height") == 0) c.common.height = c.common.width;
  c.camera = f.camera;
  c.frame_given = app.count("--frame") > 0;
  c.compare = f.compare;
  c.reps = app.count("--reps") > 0 ? f.reps : 1;
  c.reflection.glossy_rays = app.count("--glossy-rays") > 0 ? f.glossy_rays : 8;
  c.reflection.area_light_samples = f.light_samples;
  c.cube_size = f.cube_size;
  c.d_e = f.d_e;
  c.distance = f.distance;
  c.edge_fallback = f.edge == "fallback";
  return run_cluster_reflect(c);
}

}  // namespace

Command register_reflect(CLI::App& root) {
  static ReflectFlags f;
  static ClusterReflectFlags cluster;
  auto* app = root.add_subcommand(
      "reflect",
      "reflections through environment maps with distance (plain, rectified, average, layered) or clustered "
      "depth images (cluster) vs Embree");
  add_scene_flag(app, f.common, "room-reflector");
  add_camera_flags(app, f.camera);
  f.common.width = 1024;
  f.common.height = 768;
  add_size_flags(app, f.common);
  add_threads_flag(app, f.common);
  add_seed_flag(app, f.common);
  add_out_flag(app, f.common, true);
  app->add_option("--method", f.method, "envmap | rectified | average | layered | reference | cluster | temporal")
      ->capture_default_str();
  app->add_flag("--compare", f.compare,
                "render every method and the reference; errors and the timing table (cluster: Embree on the "
                "same rays and rectified env mapping)");
  app->add_option("--d-e", f.d_e, "rectification tolerance d_e in meters")->capture_default_str();
  app->add_option("--distance", f.distance, "search length D in meters (0 = scene bounding-box diagonal)")
      ->capture_default_str();
  app->add_option("--cube-size", f.cube_size, "cube map face resolution")->capture_default_str();
  app->add_option("--angle-step", f.angle_step_deg, "sampling step s of the average distance, degrees")
      ->capture_default_str();
  app->add_option("--edge", f.edge, "edge rule when the search ends beside the environment: black | fallback")
      ->capture_default_str();
  app->add_option("--light-samples", f.light_samples, "N×N samples per area light")->capture_default_str();
  app->add_option("--glossy-rays,--gloss-rays", f.glossy_rays, "rays (lookups) per glossy lobe (cluster: 8)")
      ->capture_default_str();
  app->add_option("--layers", f.layers,
                  "layered: depth layers peeled from the map's center (layer 0 = the ordinary distance map)")
      ->capture_default_str();
  app->add_option("--march-steps", f.march_steps, "layered: ray-march samples per lookup at most")
      ->capture_default_str();
  app->add_option("--reps", f.reps,
                  "timed frames per method, round-robin over the methods (median reported; cluster: 1 per frame)")
      ->capture_default_str();
  // --frames, --frame-step and --image-frame are the cluster group's; temporal reads them too.
  add_cluster_reflect_flags(app, cluster);
  add_temporal_reflect_flags(app, f.temporal);

  return {
      app, [app] {
        if (f.method == "temporal") {
          if (!f.camera.camera.empty()) fail_input("--camera: --method temporal follows --path");
          if (f.camera.frame != 0) fail_input("--frame: --method temporal renders the whole path (see --frames)");
          f.temporal.frames = cluster.frames;
          f.temporal.frame_step = cluster.frame_step;
          f.temporal.image_frame = cluster.image_frame;
          TemporalReflectRun run{f.common, f.camera.path, f.compare, f.light_samples, f.glossy_rays, f.temporal};
          return run_temporal_reflect(run);
        }
        validate(f);
        if (f.method == "cluster") return run_cluster(f, *app, cluster);
        ThreadLimit limit(f.common.threads);
        Scene scene = load_scene(f.common.scene);
        Camera camera = pick_camera(scene, f.camera, f.common.width, f.common.height);
        if (has_animation(scene)) {
          // Animated objects at the path frame's time (as `proxima render`), else at 0.
          float t = 0.0f;
          for (const auto& p : scene.camera_paths)
            if (!f.camera.path.empty() && p.name == f.camera.path) t = frame_time(p, f.camera.frame);
          scene = pose_scene(scene, t);
        }
        const std::vector<uint32_t> reflectors = reflective_objects(scene);
        if (reflectors.empty()) fail_input("--scene: '" + f.common.scene + "' has no reflective object");
        auto out = prepare_out_dir(f.common.out);

        std::vector<std::string> methods;
        if (f.compare)
          methods.assign(std::begin(kMethods), std::end(kMethods));
        else
          methods = {f.method};
        auto wants = [&](const char* m) {
          return std::find(methods.begin(), methods.end(), m) != methods.end();
        };

        Results results;
        results.command = command_line();
        results.threads = active_threads();
        RayScene rays(scene);
        const vec3 center = projection_center(scene, reflectors);

        // The reference: the same camera and pixels, mirror rays one bounce deep.
        ReferenceOptions ro;
        ro.area_light_samples = f.light_samples;
        ro.glossy_rays = f.glossy_rays;
        ro.max_bounces = 1;
        ro.seed = f.common.seed;
        const ImageF reference = render_reference(scene, rays, camera, ro);
        const ItemBuffer item = trace_item_buffer(scene, rays, camera);

        // Maps: one for plain / rectified / average, K depth layers for layered. Built once
        // (a static environment), timed apart from the per-frame work.
        DistanceCubeMapOptions mo;
        mo.resolution = f.cube_size;
        mo.area_light_samples = f.light_samples;
        mo.seed = f.common.seed;
        mo.exclude = reflectors;
        const float step = glm::radians(f.angle_step_deg);
        DistanceCubeMap map;
        float d_bar = kDistanceInf;
        if (wants("envmap") || wants("rectified") || wants("average")) {
          Stopwatch w;
          map = render_distance_cube_map(scene, rays, center, mo);
          results.metrics["envmap_build_ms"] = w.elapsed_ms();
          w.restart();
          d_bar = average_distance(map, step);
          results.metrics["average_distance_ms"] = w.elapsed_ms();
          results.metrics["average_distance_m"] = d_bar;
        }
        std::vector<DistanceCubeMap> layers;
        if (wants("layered")) {
          DistanceCubeLayerOptions lo;
          lo.layers = f.layers;
          lo.viewer_radius = viewer_radius(scene, reflectors, center);
          Stopwatch w;
          layers = render_distance_cube_layers(scene, rays, center, mo, lo);
          results.metrics["layered_build_ms"] = w.elapsed_ms();
          results.metrics["layers"] = double(layers.size());
          results.metrics["viewer_radius_m"] = lo.viewer_radius;
          for (size_t k = 0; k < layers.size(); ++k) {
            results.metrics["layer" + std::to_string(k) + "_shaded_texels"] = double(layers[k].shaded_texels);
            results.metrics["layer" + std::to_string(k) + "_hidden_texels"] = double(layers[k].hidden_texels);
          }
        }

        EnvmapInputs in;
        in.map = &map;
        in.average_distance = d_bar;
        in.layers = layers;
        in.rectify.D = f.distance > 0.0f ? f.distance : scene_bounds(scene).diagonal();
        in.rectify.d_e = f.d_e;
        in.rectify.edge = f.edge == "fallback" ? EdgeRule::PlainFallback : EdgeRule::Black;
        in.rectify.max_march_steps = f.march_steps;
        in.area_light_samples = f.light_samples;
        in.glossy_rays = f.glossy_rays;
        in.seed = f.common.seed;
        results.metrics["D_m"] = in.rectify.D;
        results.metrics["d_e_m"] = f.d_e;
        results.metrics["N"] = rectify_step_limit(in.rectify.D, f.d_e);

        const ReflectorPixels pixels = rasterize_reflector_pixels(scene, camera, reflectors);
        size_t mask_pixels = 0;
        const ImageU8 mask = comparison_mask(pixels, item, scene, reflectors, &mask_pixels);
        results.metrics["reflector_pixels"] = double(mask_pixels);
        const ImageU32 reference_objects = reference_reflected_objects(scene, rays, camera, item, mask);
        // Pixels whose mirror ray meets the environment, not the reflector itself: no map
        // of the environment (the reflector excluded) can show self-reflections.
        ImageU8 env_mask = mask;
        size_t self_pixels = 0;
        for (size_t i = 0; i < env_mask.data().size(); ++i) {
          const uint32_t o = reference_objects.data()[i];
          if (env_mask.data()[i] && std::find(reflectors.begin(), reflectors.end(), o) != reflectors.end()) {
            env_mask.data()[i] = 0;
            ++self_pixels;
          }
        }
        results.metrics["self_reflection_pct"] =
            mask_pixels ? 100.0 * double(self_pixels) / double(mask_pixels) : 0.0;

        Table table{"reflect " + scene.name + " (" + std::to_string(camera.width) + "x" +
                        std::to_string(camera.height) + ", cube " + std::to_string(f.cube_size) + "², d_e " +
                        std::to_string(f.d_e).substr(0, 5) + ")",
                    {"method", "ms_per_frame", "fps", "ms_with_map_build", "mae_0_255", "env_mae_0_255",
                     "object_match_pct", "edge_pct"},
                    {}};
        // A method's frame: the reflector's visibility (rasterized) and its shading.
        auto frame_of = [&](const std::string& m) {
          in.method = parse_method(m);
          return shade_reflector_pixels(scene, rays, camera,
                                        rasterize_reflector_pixels(scene, camera, reflectors), in);
        };
        // Outputs (and warm-up) first, then the timed frames round-robin over the methods,
        // so load changes on the shared machine hit every method alike.
        std::vector<EnvmapFrame> frames(methods.size());
        for (size_t i = 0; i < methods.size(); ++i)
          if (methods[i] != "reference") frames[i] = frame_of(methods[i]);
        std::vector<std::vector<double>> times(methods.size());
        for (int r = 0; r < f.reps; ++r)
          for (size_t i = 0; i < methods.size(); ++i) {
            Stopwatch w;
            if (methods[i] == "reference")
              render_reference(scene, rays, camera, ro);
            else
              frame_of(methods[i]);
            times[i].push_back(w.elapsed_ms());
          }

        for (size_t i = 0; i < methods.size(); ++i) {
          const std::string& m = methods[i];
          const EnvmapFrame& frame = frames[i];
          const double ms = median(times[i]);
          double with_build = ms, edge_pct = 0.0, match_pct = 100.0;
          ImageF color = reference;
          if (m != "reference") {
            with_build += results.metrics[m == "layered" ? "layered_build_ms" : "envmap_build_ms"];
            edge_pct = frame.stats.lookups
                           ? 100.0 * double(frame.stats.edge_lookups) / double(frame.stats.lookups)
                           : 0.0;
            results.metrics[m + "_edge_pct"] = edge_pct;
            if (m == "layered")
              results.metrics["layered_fallback_pct"] =
                  frame.stats.lookups ? 100.0 * double(frame.stats.fallback_lookups) / double(frame.stats.lookups)
                                      : 0.0;
            match_pct = object_match_pct(frame.object, reference_objects, mask, mask_pixels);
            results.metrics[m + "_samples_per_lookup"] =
                frame.stats.lookups ? double(frame.stats.map_samples) / double(frame.stats.lookups) : 0.0;
            // Outside the reflector the image is the reference's: only the reflection differs.
            for (int y = 0; y < color.height(); ++y)
              for (int x = 0; x < color.width(); ++x)
                if (pixels.triangle.at(x, y) != kNoTriangle)
                  for (int c = 0; c < 3; ++c) color.at(x, y, c) = frame.color.at(x, y, c);
          }
          // eval/image_error.h: 0–255 on the displayed sRGB scale, channels averaged.
          const double mae = compare_images(color, reference, &mask).mae_avg;
          const double env_mae = compare_images(color, reference, &env_mask).mae_avg;
          results.metrics[m + "_mae"] = mae;
          results.metrics[m + "_env_mae"] = env_mae;
          results.metrics[m + "_ms"] = ms;
          results.metrics[m + "_with_build_ms"] = with_build;
          results.metrics[m + "_object_match_pct"] = match_pct;
          write_png_linear(out / (m + ".png"), color);
          results.images[m] = m + ".png";
          if (m != "reference") {
            // One scale for every method: black 0 … yellow ≥ kHeatmapMax.
            write_png_linear(out / ("error_" + m + ".png"),
                             error_heatmap(error_image(color, reference, &mask), kHeatmapMax, &mask));
            results.images["error_" + m] = "error_" + m + ".png";
          }
          table.rows.push_back({m, ms, 1000.0 / ms, with_build, mae, env_mae, match_pct, edge_pct});
        }
        results.tables.push_back(std::move(table));
        publish_results(out, results);
        return 0;
      }};
}

}  // namespace proxima::cli
