// `proxima shadows`: soft shadows from a rectangular area light through depth images
// reconstructed into occluder meshes (thesis ch. 3, Algorithms 4 and 5), measured
// against shadow maps of the original geometry and against exact Embree shadow rays
// (docs/shadows.md).
#include <cmath>
#include <string>
#include <vector>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/load.h"
#include "proxima/shadows/light_visibility.h"
#include "proxima/shadows/occluders.h"
#include "proxima/shadows/shadow_error.h"

namespace proxima::cli {

namespace {

struct ShadowsFlags {
  CommonOptions common;
  CameraChoice camera;
  std::vector<std::string> samplings{"nrr"};
  float light_size = 1.0f;
  int light_samples = 16;
  int ref_res = 1024;
  int out_res = 512;
  int shadow_res = 1024;
  std::string redundancy = "pixel";
  std::string reconstruction = "hybrid";
  bool no_rays = false;
  bool no_images = false;
};

std::string pair_text(double mean, double max) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f/%.0f", mean, max);
  return buf;
}

}  // namespace

Command register_shadows(CLI::App& root) {
  static ShadowsFlags f;
  auto* app = root.add_subcommand("shadows", "soft shadows from an area light through depth images reconstructed into "
                                             "meshes (NRR, conventional, peeling), vs shadow maps of the geometry and "
                                             "Embree shadow rays");
  add_scene_flag(app, f.common, "nest");
  add_camera_flags(app, f.camera);
  add_threads_flag(app, f.common);
  add_out_flag(app, f.common, true);
  app->add_option("--sampling", f.samplings,
                  "nrr|conventional|peeling|geometry; several, comma-separated, share the ground truth")
      ->delimiter(',')
      ->capture_default_str();
  app->add_option("--light-size", f.light_size, "light diagonal / scene bounding-box diagonal")->capture_default_str();
  app->add_option("--light-samples", f.light_samples, "n: the light is sampled n x n")->capture_default_str();
  app->add_option("--ref-res", f.ref_res, "reference depth images, pixels (square)")->capture_default_str();
  app->add_option("--out-res", f.out_res, "output image, pixels (square)")->capture_default_str();
  app->add_option("--shadow-res", f.shadow_res, "shadow maps, pixels (square)")->capture_default_str();
  app->add_option("--redundancy", f.redundancy, "pixel|visibility: NRR's redundancy test")->capture_default_str();
  app->add_option("--reconstruction", f.reconstruction, "hybrid (Algorithm 4) | conventional mesh")
      ->capture_default_str();
  app->add_flag("--no-rays", f.no_rays, "skip the Embree shadow-ray ground truth");
  app->add_flag("--no-images", f.no_images, "write results.json only");

  return {app, [] {
            // Every input checked before the output directory exists.
            if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
            if (!(f.light_size > 0.0f && f.light_size <= 100.0f)) fail_input("--light-size: must be in (0, 100]");
            if (f.light_samples < 1 || f.light_samples > 64) fail_input("--light-samples: must be in 1..64");
            if (f.ref_res < 8 || f.ref_res > 4096) fail_input("--ref-res: must be in 8..4096");
            if (f.out_res < 8 || f.out_res > 4096) fail_input("--out-res: must be in 8..4096");
            if (f.shadow_res < 8 || f.shadow_res > 8192) fail_input("--shadow-res: must be in 8..8192");
            std::vector<ShadowSampling> samplings;
            for (const std::string& s : f.samplings) samplings.push_back(parse_shadow_sampling(s, "--sampling"));
            if (samplings.empty()) fail_input("--sampling: give at least one");
            OccluderOptions occ;
            occ.resolution = f.ref_res;
            if (f.redundancy == "visibility") occ.redundancy = Redundancy::Visibility;
            else if (f.redundancy != "pixel") fail_input("--redundancy: must be pixel or visibility");
            occ.reconstruction = parse_reconstruction(f.reconstruction, "--reconstruction");

            ThreadLimit limit(f.common.threads);
            const Scene scene = load_scene(f.common.scene);
            const Camera view = pick_camera(scene, f.camera, f.out_res, f.out_res);
            const auto out = prepare_out_dir(f.common.out);

            Results results;
            results.command = command_line();
            results.threads = active_threads();
            const RayScene rays(scene);
            const AreaLight light = shadow_light(scene, f.light_size);
            const std::vector<vec3> samples = light_samples(light, f.light_samples);
            const Receivers receivers = render_receivers(scene, view);
            std::vector<vec3> eyes = samples;
            for (const vec3& c : light_corners(light)) eyes.push_back(c);
            const LightCameras cams = fit_light_cameras(scene, light, receivers, eyes);
            ShadowMapOptions sm;
            sm.resolution = f.shadow_res;

            // Ground truths: shadow maps of the original geometry, and Embree rays.
            double truth_ms = 0.0, rays_ms = 0.0;
            const LightVisibility truth = shadow_map_visibility(scene, receivers, samples, cams, sm, &truth_ms);
            LightVisibility exact;
            if (!f.no_rays) exact = ray_visibility(rays, scene, receivers, samples, &rays_ms);

            const std::string setting = scene.name + ", light " + std::to_string(f.light_size).substr(0, 5) + " x diag, " +
                                        std::to_string(f.light_samples) + "x" + std::to_string(f.light_samples) +
                                        " samples, ref " + std::to_string(f.ref_res) + ", out " +
                                        std::to_string(f.out_res) + ", shadow maps " + std::to_string(f.shadow_res);
            Table table8{"Soft-shadow error vs shadow maps of the geometry, mean/max (thesis Table 8): " + setting,
                         {"sampling", "intensity error", "visibility error"}, {}};
            Table table_rays{"Soft-shadow error vs Embree shadow rays, mean/max: " + setting,
                             {"sampling", "intensity error", "visibility error"}, {}};
            Table table11{"Time per step, ms (thesis Table 11): " + setting,
                          {"sampling", "1: reference images", "2: reconstruction", "3: soft shadows", "occluder triangles"},
                          {}};
            table11.rows.push_back({"geometry (ground truth)", 0.0, 0.0, truth_ms, double(scene.triangles.size())});
            if (!f.no_rays) {
              const ShadowError g = compare_visibility(truth, exact, receivers);
              table_rays.rows.push_back({"geometry shadow maps", pair_text(g.intensity_mean, g.intensity_max),
                                         pair_text(g.visibility_mean, g.visibility_max)});
              results.metrics["geometry_vs_rays_intensity_error_mean"] = g.intensity_mean;
              results.metrics["geometry_vs_rays_visibility_error_mean"] = g.visibility_mean;
              results.metrics["time_rays_ms"] = rays_ms;
            }
            if (!f.no_images) {
              write_png_linear(out / "geometry_shadow.png", shadow_image(truth, receivers));
              results.images["geometry_shadow"] = "geometry_shadow.png";
              if (!f.no_rays) {
                write_png_linear(out / "rays_shadow.png", shadow_image(exact, receivers));
                results.images["rays_shadow"] = "rays_shadow.png";
              }
            }

            const bool prefixed = samplings.size() > 1;
            for (ShadowSampling s : samplings) {
              const std::string name = shadow_sampling_name(s);
              const std::string p = prefixed ? name + "_" : "";
              const Occluders occ_set = build_occluders(scene, &rays, light, cams, s, occ);
              double shadow_ms = 0.0;
              const LightVisibility v = s == ShadowSampling::Geometry
                                            ? truth
                                            : shadow_map_visibility(occ_set.scene, receivers, samples, cams, sm, &shadow_ms);
              if (s == ShadowSampling::Geometry) shadow_ms = truth_ms;
              const ShadowError e = compare_visibility(v, truth, receivers);
              results.metrics[p + "intensity_error_mean"] = e.intensity_mean;
              results.metrics[p + "intensity_error_max"] = e.intensity_max;
              results.metrics[p + "visibility_error_mean"] = e.visibility_mean;
              results.metrics[p + "visibility_error_max"] = e.visibility_max;
              results.metrics[p + "time_reference_ms"] = occ_set.reference_ms;
              results.metrics[p + "time_reconstruct_ms"] = occ_set.reconstruct_ms;
              results.metrics[p + "time_shadow_ms"] = shadow_ms;
              results.metrics[p + "occluder_triangles"] = double(occ_set.scene.triangles.size());
              results.metrics[p + "reference_samples"] = double(occ_set.samples);
              table8.rows.push_back({name, pair_text(e.intensity_mean, e.intensity_max),
                                     pair_text(e.visibility_mean, e.visibility_max)});
              table11.rows.push_back({name, occ_set.reference_ms, occ_set.reconstruct_ms, shadow_ms,
                                      double(occ_set.scene.triangles.size())});
              if (!f.no_rays) {
                const ShadowError r = compare_visibility(v, exact, receivers);
                results.metrics[p + "intensity_error_rays_mean"] = r.intensity_mean;
                results.metrics[p + "intensity_error_rays_max"] = r.intensity_max;
                results.metrics[p + "visibility_error_rays_mean"] = r.visibility_mean;
                results.metrics[p + "visibility_error_rays_max"] = r.visibility_max;
                table_rays.rows.push_back({name, pair_text(r.intensity_mean, r.intensity_max),
                                           pair_text(r.visibility_mean, r.visibility_max)});
              }
              if (!f.no_images) {
                write_png_linear(out / (name + "_shadow.png"), shadow_image(v, receivers));
                write_png_linear(out / (name + "_error.png"), e.image);
                results.images[name + "_shadow"] = name + "_shadow.png";
                results.images[name + "_error"] = name + "_error.png";
              }
            }
            results.metrics["light_size"] = f.light_size;
            results.metrics["light_samples"] = double(samples.size());
            results.metrics["receivers"] = double(receivers.count);
            results.metrics["triangles"] = double(scene.triangles.size());
            results.metrics["light_fov_deg"] = cams.vfov_deg;
            results.tables.push_back(table8);
            if (!f.no_rays) results.tables.push_back(table_rays);
            results.tables.push_back(table11);
            publish_results(out, results);
            return 0;
          }};
}

}  // namespace proxima::cli
